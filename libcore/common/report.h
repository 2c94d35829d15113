// A small ordered tree of named values that tools print either as indented text for
// people or as JSON for scripts (bw-info --json, bw-voronoi check --json, run
// summaries). Keys keep their insertion order.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace bw {

class Report {
 public:
  using Numbers = std::vector<double>;
  // A table: column names and rows of numbers (per-frame statistics, ...).
  struct Table {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
  };

  Report& set(const std::string& key, const std::string& value);
  Report& set(const std::string& key, const char* value) { return set(key, std::string(value)); }
  Report& set(const std::string& key, double value);
  Report& set(const std::string& key, std::int64_t value);
  Report& set(const std::string& key, std::uint64_t value) { return set(key, static_cast<std::int64_t>(value)); }
  Report& set(const std::string& key, int value) { return set(key, static_cast<std::int64_t>(value)); }
  Report& set(const std::string& key, bool value);
  Report& set(const std::string& key, Numbers values);
  Report& set(const std::string& key, Table table);
  // A nested report under `key` (created on first use).
  Report& child(const std::string& key);
  // Appends an element to the list `key` and returns it.
  Report& append(const std::string& key);

  std::string to_json(int indent = 2) const;
  std::string to_text() const;

 private:
  using List = std::vector<Report>;
  using Value = std::variant<std::string, double, std::int64_t, bool, Numbers, Table, std::shared_ptr<Report>,
                             std::shared_ptr<List>>;
  Value* find(const std::string& key);
  void put(const std::string& key, Value value);
  void json(std::string& out, int indent, int depth) const;
  void text(std::string& out, int depth) const;

  std::vector<std::pair<std::string, Value>> entries_;
};

}  // namespace bw
