#include "sim/ros2/rosbag2_reader.hpp"

#include "sim/ros2/mcap_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

namespace fs = std::filesystem;

bool isSqliteFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[16] = {};
  return in.read(magic, 16) && std::string(magic, 15) == "SQLite format 3";
}

std::unique_ptr<Rosbag2Storage> openStorage(const std::string& file, const std::string& identifier) {
  if (identifier == "mcap") return openMcapStorage(file);
  if (identifier == "sqlite3") return openSqlite3Storage(file);
  throw std::runtime_error(file + ": storage '" + identifier + "' unknown (bimloc reads sqlite3 and mcap)");
}

std::string identifierOf(const std::string& file) {
  if (isMcapFile(file)) return "mcap";
  if (isSqliteFile(file)) return "sqlite3";
  const std::string ext = fs::path(file).extension().string();
  return ext == ".mcap" ? "mcap" : ext == ".db3" ? "sqlite3" : "";
}

}  // namespace

bool isRosbag2(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    if (fs::exists(fs::path(path) / "metadata.yaml", ec)) return true;
    for (const auto& e : fs::directory_iterator(path, ec)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".db3" || ext == ".mcap") return true;
    }
    return false;
  }
  return isMcapFile(path) || isSqliteFile(path);
}

Rosbag2Reader::~Rosbag2Reader() = default;

Rosbag2Reader::Rosbag2Reader(const std::string& path) : path_(path) {
  std::vector<std::string> files;
  std::map<std::string, std::uint64_t> metadata_counts;  // topic: messages, as metadata.yaml says
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error(path + ": no such file or folder");
  if (fs::is_directory(path, ec)) {
    const fs::path metadata = fs::path(path) / "metadata.yaml";
    if (fs::exists(metadata, ec)) {
      YAML::Node info;
      try {
        info = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
      } catch (const YAML::Exception& e) {
        throw std::runtime_error(metadata.string() + ": not YAML: " + e.what());
      }
      if (!info || !info.IsMap()) throw std::runtime_error(metadata.string() + ": no rosbag2_bagfile_information (not a rosbag2 metadata file)");
      try {
        storage_ = info["storage_identifier"] ? info["storage_identifier"].as<std::string>() : "";
        const std::string compression = info["compression_format"] ? info["compression_format"].as<std::string>() : "";
        if (!compression.empty())
          throw std::runtime_error(metadata.string() + ": compressed by rosbag2 (compression_format " + compression +
                                   ", mode " + (info["compression_mode"] ? info["compression_mode"].as<std::string>() : "?") +
                                   "), which bimloc does not read: 'ros2 bag decompress' it first");
        if (info["topics_with_message_count"])
          for (const auto& t : info["topics_with_message_count"])
            metadata_counts[t["topic_metadata"]["name"].as<std::string>()] = t["message_count"].as<std::uint64_t>();
        if (info["relative_file_paths"])
          for (const auto& f : info["relative_file_paths"]) files.push_back((fs::path(path) / f.as<std::string>()).string());
      } catch (const YAML::Exception& e) {
        throw std::runtime_error(metadata.string() + ": " + e.what());
      }
      if (files.empty()) throw std::runtime_error(metadata.string() + ": relative_file_paths lists no storage file");
      for (const auto& f : files)
        if (!fs::exists(f, ec)) throw std::runtime_error(metadata.string() + ": lists " + f + ", which does not exist");
    } else {
      for (const auto& e : fs::directory_iterator(path, ec)) {
        const std::string ext = e.path().extension().string();
        if (ext == ".db3" || ext == ".mcap") files.push_back(e.path().string());
      }
      std::sort(files.begin(), files.end());
      if (files.empty()) throw std::runtime_error(path + ": a folder with neither metadata.yaml nor .db3 / .mcap files (not a ROS 2 bag)");
      warnings_.push_back(path + ": no metadata.yaml: read its " + std::to_string(files.size()) + " storage file(s) in name order");
    }
  } else {
    files.push_back(path);
  }
  for (const auto& f : files) {
    const std::string identifier = storage_.empty() ? identifierOf(f) : storage_;
    if (identifier.empty()) throw std::runtime_error(f + ": neither MCAP nor SQLite3 (not a ROS 2 bag)");
    if (storage_.empty()) storage_ = identifier;
    files_.push_back(openStorage(f, identifier));
    for (const auto& w : files_.back()->warnings()) warnings_.push_back(w);
  }
  std::map<std::string, std::size_t> by_name;
  for (const auto& file : files_)
    for (const BagTopic& t : file->topics()) {
      const auto it = by_name.find(t.name);
      if (it == by_name.end()) {
        by_name[t.name] = topics_.size();
        topics_.push_back(t);
      } else {
        topics_[it->second].messages += t.messages;
      }
    }
  // A storage file that lost messages (cut, damaged) against what the recorder counted.
  for (const auto& [name, expected] : metadata_counts) {
    const BagTopic* t = topic(name);
    const std::uint64_t found = t ? t->messages : 0;
    if (found != expected)
      warnings_.push_back(path + ": metadata.yaml counts " + std::to_string(expected) + " messages on " + name + ", the storage has " +
                          std::to_string(found));
  }
}

const BagTopic* Rosbag2Reader::topic(const std::string& name) const {
  for (const auto& t : topics_)
    if (t.name == name) return &t;
  return nullptr;
}

std::string Rosbag2Reader::topicList() const {
  std::ostringstream out;
  std::vector<const BagTopic*> sorted;
  for (const auto& t : topics_) sorted.push_back(&t);
  std::sort(sorted.begin(), sorted.end(), [](const auto* a, const auto* b) { return a->name < b->name; });
  for (const auto* t : sorted) out << "\n  " << t->name << " (" << t->type << ", " << t->messages << " messages)";
  if (topics_.empty()) out << "\n  (none)";
  return out.str();
}

std::vector<std::uint64_t> Rosbag2Storage::logTimes(const std::string& topic) const {
  std::vector<std::uint64_t> times;
  forEachMessage({topic}, [&](const BagMessage& m) { times.push_back(m.log_time_ns); });
  return times;
}

std::vector<std::uint64_t> Rosbag2Reader::logTimes(const std::string& topic) const {
  std::vector<std::uint64_t> times;
  for (const auto& file : files_) {
    const auto t = file->logTimes(topic);
    times.insert(times.end(), t.begin(), t.end());
  }
  return times;
}

void Rosbag2Reader::forEachMessage(const std::vector<std::string>& topics, const std::function<void(const BagMessage&)>& visit,
                                   ReadPlan plan) const {
  for (const auto& file : files_) {
    file->forEachMessage(topics, [&](const BagMessage& m) {
      BagMessage out = m;
      out.topic = topic(m.topic->name);  // the bag's topic, its count over every file
      visit(out);
    }, plan);
  }
}

}  // namespace bimloc::sim::ros2
