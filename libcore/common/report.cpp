#include "common/report.h"

#include <cmath>

#include <fmt/format.h>

#include "common/text.h"

namespace bw {
namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no NaN or infinity
  return fmt::format("{}", v);           // shortest representation that reads back exactly
}

std::string pad(int n) { return std::string(static_cast<std::size_t>(std::max(n, 0)), ' '); }

}  // namespace

Report::Value* Report::find(const std::string& key) {
  for (auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

void Report::put(const std::string& key, Value value) {
  if (Value* existing = find(key)) *existing = std::move(value);
  else entries_.emplace_back(key, std::move(value));
}

Report& Report::set(const std::string& key, const std::string& value) { put(key, value); return *this; }
Report& Report::set(const std::string& key, double value) { put(key, value); return *this; }
Report& Report::set(const std::string& key, std::int64_t value) { put(key, value); return *this; }
Report& Report::set(const std::string& key, bool value) { put(key, value); return *this; }
Report& Report::set(const std::string& key, Numbers values) { put(key, std::move(values)); return *this; }
Report& Report::set(const std::string& key, Table table) { put(key, std::move(table)); return *this; }

Report& Report::child(const std::string& key) {
  if (Value* existing = find(key)) {
    if (auto* nested = std::get_if<std::shared_ptr<Report>>(existing)) return **nested;
  }
  auto nested = std::make_shared<Report>();
  put(key, nested);
  return *nested;
}

Report& Report::append(const std::string& key) {
  Value* existing = find(key);
  if (!existing || !std::holds_alternative<std::shared_ptr<List>>(*existing)) {
    put(key, std::make_shared<List>());
    existing = find(key);
  }
  auto& list = *std::get<std::shared_ptr<List>>(*existing);
  list.emplace_back();
  return list.back();
}

void Report::json(std::string& out, int indent, int depth) const {
  const std::string nl = indent > 0 ? "\n" : "";
  const std::string in = pad(indent * (depth + 1));
  out += "{" + nl;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const auto& [key, value] = entries_[i];
    out += in + json_quote(key) + (indent > 0 ? ": " : ":");
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::string>) out += json_quote(v);
          else if constexpr (std::is_same_v<T, double>) out += number(v);
          else if constexpr (std::is_same_v<T, std::int64_t>) out += std::to_string(v);
          else if constexpr (std::is_same_v<T, bool>) out += v ? "true" : "false";
          else if constexpr (std::is_same_v<T, Numbers>) {
            out += "[";
            for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + number(v[k]);
            out += "]";
          } else if constexpr (std::is_same_v<T, Table>) {
            // A table is a list of objects, one per row: easy to load in any language.
            out += "[";
            for (std::size_t r = 0; r < v.rows.size(); ++r) {
              out += (r ? "," : "") + nl + pad(indent * (depth + 2)) + "{";
              for (std::size_t c = 0; c < v.columns.size() && c < v.rows[r].size(); ++c) {
                out += (c ? ", " : "") + json_quote(v.columns[c]) + ": " + number(v.rows[r][c]);
              }
              out += "}";
            }
            out += (v.rows.empty() ? "" : nl + in) + "]";
          } else if constexpr (std::is_same_v<T, std::shared_ptr<Report>>) {
            v->json(out, indent, depth + 1);
          } else if constexpr (std::is_same_v<T, std::shared_ptr<List>>) {
            out += "[";
            for (std::size_t k = 0; k < v->size(); ++k) {
              out += (k ? "," : "") + nl + pad(indent * (depth + 2));
              (*v)[k].json(out, indent, depth + 2);
            }
            out += (v->empty() ? "" : nl + in) + "]";
          }
        },
        value);
    out += (i + 1 < entries_.size() ? "," : "") + nl;
  }
  out += pad(indent * depth) + "}";
}

void Report::text(std::string& out, int depth) const {
  const std::string in = pad(2 * depth);
  for (const auto& [key, value] : entries_) {
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::string>) out += in + key + ": " + v + "\n";
          else if constexpr (std::is_same_v<T, double>) out += in + key + ": " + fmt::format("{:.6g}", v) + "\n";
          else if constexpr (std::is_same_v<T, std::int64_t>) out += in + key + ": " + std::to_string(v) + "\n";
          else if constexpr (std::is_same_v<T, bool>) out += in + key + ": " + (v ? "yes" : "no") + "\n";
          else if constexpr (std::is_same_v<T, Numbers>) {
            out += in + key + ":";
            for (double x : v) out += fmt::format(" {:.6g}", x);
            out += "\n";
          } else if constexpr (std::is_same_v<T, Table>) {
            out += in + key + ": " + std::to_string(v.rows.size()) + " rows\n" + in + " ";
            for (const auto& c : v.columns) out += fmt::format(" {:>12}", c);
            out += "\n";
            for (const auto& row : v.rows) {
              out += in + " ";
              for (double x : row) out += fmt::format(" {:>12.6g}", x);
              out += "\n";
            }
          } else if constexpr (std::is_same_v<T, std::shared_ptr<Report>>) {
            out += in + key + ":\n";
            v->text(out, depth + 1);
          } else if constexpr (std::is_same_v<T, std::shared_ptr<List>>) {
            for (std::size_t k = 0; k < v->size(); ++k) {
              out += in + key + "[" + std::to_string(k) + "]:\n";
              (*v)[k].text(out, depth + 1);
            }
          }
        },
        value);
  }
}

std::string Report::to_json(int indent) const {
  std::string out;
  json(out, indent, 0);
  return out + "\n";
}

std::string Report::to_text() const {
  std::string out;
  text(out, 0);
  return out;
}

}  // namespace bw
