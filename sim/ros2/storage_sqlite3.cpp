// rosbag2's SQLite3 storage (rosbag2_storage_default_plugins, the default before Iron):
// a table `topics` (id, name, type, serialization_format, offered_qos_profiles) and a table
// `messages` (id, topic_id, timestamp, data), the timestamp in nanoseconds.
#include "sim/ros2/rosbag2_reader.hpp"

#include <sqlite3.h>

#include <map>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& path) : path_(path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(path + ": not a rosbag2 SQLite3 file: " + sqlite3_errmsg(db));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  // True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(path_ + ": damaged SQLite3 file: " + sqlite3_errmsg(sqlite3_db_handle(stmt_)));
  }
  std::string text(int column) const {
    const auto* p = sqlite3_column_text(stmt_, column);
    return p ? reinterpret_cast<const char*>(p) : "";
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(stmt_, column); }
  sqlite3_stmt* get() { return stmt_; }

 private:
  sqlite3_stmt* stmt_ = nullptr;
  std::string path_;
};

class SqliteStorage final : public Rosbag2Storage {
 public:
  explicit SqliteStorage(const std::string& path) : path_(path) {
    // immutable: no lock, no journal, so a bag on a read-only disk opens.
    const std::string uri = "file:" + path + "?immutable=1";
    if (sqlite3_open_v2(uri.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) != SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw std::runtime_error(path + ": cannot open as SQLite3: " + why);
    }
    try {
      // Pages read from a memory map rather than copied into SQLite's page cache by read():
      // a bag is read once, front to back, and a cloud's row spans a few hundred pages.
      sqlite3_exec(db_, "PRAGMA mmap_size = 2147418112", nullptr, nullptr, nullptr);  // SQLite's default ceiling
      {
        Statement topics(db_, "SELECT id, name, type, serialization_format FROM topics ORDER BY id", path);
        while (topics.step()) {
          BagTopic t;
          t.name = topics.text(1), t.type = topics.text(2), t.serialization_format = topics.text(3);
          ids_[t.name] = topics.integer(0);
          index_[topics.integer(0)] = topics_.size();
          topics_.push_back(std::move(t));
        }
      }
      {  // offered_qos_profiles: from metadata version 4 on; older bags lack the column
        sqlite3_stmt* probe = nullptr;
        if (sqlite3_prepare_v2(db_, "SELECT id, offered_qos_profiles FROM topics", -1, &probe, nullptr) == SQLITE_OK) {
          while (sqlite3_step(probe) == SQLITE_ROW) {
            const auto it = index_.find(sqlite3_column_int64(probe, 0));
            const auto* q = sqlite3_column_text(probe, 1);
            if (it != index_.end() && q) topics_[it->second].offered_qos_profiles = reinterpret_cast<const char*>(q);
          }
        }
        sqlite3_finalize(probe);
      }
      Statement counts(db_, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id", path);
      while (counts.step()) {
        const auto it = index_.find(counts.integer(0));
        if (it == index_.end()) {
          warnings_.push_back(path + ": " + std::to_string(counts.integer(1)) + " messages of topic id " +
                              std::to_string(counts.integer(0)) + ", which the topics table does not have: ignored");
          continue;
        }
        topics_[it->second].messages = static_cast<std::uint64_t>(counts.integer(1));
      }
    } catch (...) {
      sqlite3_close(db_);
      throw;
    }
  }
  ~SqliteStorage() override { sqlite3_close(db_); }

  const std::vector<BagTopic>& topics() const override { return topics_; }
  const std::vector<std::string>& warnings() const override { return warnings_; }

  std::vector<std::uint64_t> logTimes(const std::string& topic) const override {
    std::vector<std::uint64_t> times;
    const auto it = ids_.find(topic);
    if (it == ids_.end()) return times;
    Statement rows(db_, "SELECT timestamp FROM messages WHERE topic_id = " + std::to_string(it->second) + " ORDER BY timestamp, id", path_);
    while (rows.step()) {
      if (rows.integer(0) < 0) throw std::runtime_error(path_ + ": " + topic + ": a negative timestamp " + std::to_string(rows.integer(0)));
      times.push_back(static_cast<std::uint64_t>(rows.integer(0)));
    }
    return times;
  }

  void forEachMessage(const std::vector<std::string>& names, const std::function<void(const BagMessage&)>& visit,
                      ReadPlan /*plan: no chunks*/) const override {
    std::string where_ids;
    for (const auto& n : names) {
      const auto it = ids_.find(n);
      if (it == ids_.end()) continue;
      where_ids += (where_ids.empty() ? "" : ",") + std::to_string(it->second);
    }
    if (!names.empty() && where_ids.empty()) return;
    Statement rows(db_,
                   "SELECT topic_id, timestamp, data FROM messages" +
                       (names.empty() ? std::string() : " WHERE topic_id IN (" + where_ids + ")") + " ORDER BY timestamp, id",
                   path_);
    std::map<std::int64_t, std::uint64_t> seen;
    while (rows.step()) {
      const auto it = index_.find(rows.integer(0));
      if (it == index_.end()) continue;
      BagMessage m;
      m.topic = &topics_[it->second];
      const std::int64_t stamp = rows.integer(1);
      if (stamp < 0) throw std::runtime_error(path_ + ": " + m.topic->name + ": a negative timestamp " + std::to_string(stamp));
      m.log_time_ns = static_cast<std::uint64_t>(stamp);
      m.data = static_cast<const std::uint8_t*>(sqlite3_column_blob(rows.get(), 2));
      m.size = static_cast<std::size_t>(sqlite3_column_bytes(rows.get(), 2));
      m.where = path_ + ": " + m.topic->name + " message " + std::to_string(seen[rows.integer(0)]++);
      visit(m);
    }
  }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  std::vector<BagTopic> topics_;
  std::map<std::string, std::int64_t> ids_;
  std::map<std::int64_t, std::size_t> index_;  // topic id -> topics_ index
  std::vector<std::string> warnings_;
};

}  // namespace

std::unique_ptr<Rosbag2Storage> openSqlite3Storage(const std::string& path) { return std::make_unique<SqliteStorage>(path); }

}  // namespace bimloc::sim::ros2
