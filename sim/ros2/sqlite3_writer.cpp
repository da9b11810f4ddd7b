// rosbag2's SQLite3 storage, written: the schema of rosbag2_storage_default_plugins (Humble),
// one transaction for the whole bag (a bag half-written is discarded by the caller anyway).
#include "sim/ros2/rosbag2_writer.hpp"

#include <sqlite3.h>

#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

class SqliteWriter final : public Rosbag2Writer::Storage {
 public:
  explicit SqliteWriter(const std::string& path) : path_(path) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw std::runtime_error(path + ": cannot create: " + why);
    }
    exec("PRAGMA journal_mode=MEMORY; PRAGMA synchronous=OFF;"
         "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
         "INSERT INTO schema VALUES (3, 'humble');"
         "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);"
         "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
         "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
         "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
         "data BLOB NOT NULL);"
         "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
         "BEGIN;");
    prepare("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", &insert_);
  }
  ~SqliteWriter() override {
    sqlite3_finalize(insert_);
    sqlite3_close(db_);
  }

  int addTopic(const std::string& name, const std::string& type, const std::string& qos) override {
    sqlite3_stmt* s = nullptr;
    prepare("INSERT INTO topics (id, name, type, serialization_format, offered_qos_profiles) VALUES (?, ?, ?, 'cdr', ?)", &s);
    const int id = ++topics_;
    sqlite3_bind_int(s, 1, id);
    sqlite3_bind_text(s, 2, name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(s, 3, type.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(s, 4, qos.c_str(), -1, SQLITE_TRANSIENT);
    const int rc = sqlite3_step(s);
    sqlite3_finalize(s);
    if (rc != SQLITE_DONE) fail("cannot add topic " + name);
    return id;
  }

  void write(int topic, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& cdr) override {
    sqlite3_reset(insert_);
    sqlite3_bind_int(insert_, 1, topic);
    sqlite3_bind_int64(insert_, 2, static_cast<sqlite3_int64>(log_time_ns));
    sqlite3_bind_blob(insert_, 3, cdr.data(), static_cast<int>(cdr.size()), SQLITE_STATIC);
    if (sqlite3_step(insert_) != SQLITE_DONE) fail("cannot write a message");
  }

  void close() override { exec("COMMIT;"); }

 private:
  [[noreturn]] void fail(const std::string& what) { throw std::runtime_error(path_ + ": " + what + ": " + sqlite3_errmsg(db_)); }
  void exec(const char* sql) {
    char* error = nullptr;
    if (sqlite3_exec(db_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string why = error ? error : "?";
      sqlite3_free(error);
      throw std::runtime_error(path_ + ": " + why);
    }
  }
  void prepare(const char* sql, sqlite3_stmt** s) {
    if (sqlite3_prepare_v2(db_, sql, -1, s, nullptr) != SQLITE_OK) fail("cannot prepare");
  }

  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  int topics_ = 0;
};

}  // namespace

std::unique_ptr<Rosbag2Writer::Storage> createSqlite3Storage(const std::string& path) {
  return std::make_unique<SqliteWriter>(path);
}

}  // namespace bimloc::sim::ros2
