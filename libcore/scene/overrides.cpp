#include "scene/overrides.h"

#include <cctype>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "common/error.h"

namespace bw::scene {
namespace {

struct Segment {
  std::string name;
  std::optional<std::size_t> index;  // name[index]
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; }

// "fluid.block[0].min" -> {fluid}, {block, 0}, {min}. Empty when malformed.
std::vector<Segment> parse_key(std::string_view key) {
  std::vector<Segment> out;
  std::size_t i = 0;
  while (true) {
    Segment s;
    while (i < key.size() && name_char(key[i])) s.name += key[i++];
    if (s.name.empty()) return {};
    if (i < key.size() && key[i] == '[') {
      std::size_t j = ++i;
      while (j < key.size() && std::isdigit(static_cast<unsigned char>(key[j]))) ++j;
      if (j == i || j >= key.size() || key[j] != ']' || j - i > 9) return {};
      s.index = std::stoul(std::string(key.substr(i, j - i)));
      i = j + 1;
    }
    out.push_back(std::move(s));
    if (i == key.size()) return out;
    if (key[i] != '.') return {};
    ++i;
  }
}

std::string kind_of(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return n.as_array()->is_array_of_tables() ? "an array of tables" : "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

// Whether the text starts like a TOML value, so that a failure to parse it is an
// error rather than a bare string.
bool looks_like_toml(std::string_view v) {
  if (v.empty()) return false;
  const char c = v.front();
  return std::isdigit(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '"' || c == '\'' || c == '[' ||
         c == '{';
}

class Applier {
 public:
  Applier(const std::string& file, const std::string& text) : file_(file), text_(text) {}

  [[noreturn]] void fail(const std::string& problem) const {
    fail_input("{}: --set {}: {}", file_, text_, problem);
  }

  toml::table parse_value(std::string_view value) const {
    try {
      return toml::parse(fmt::format("v = {}", value));
    } catch (const toml::parse_error& e) {
      if (looks_like_toml(value)) {
        std::string what(e.description());
        for (char& c : what)
          if (c == '\n') c = ' ';
        fail(fmt::format("'{}' is not a TOML value ({}; strings that start like one need quotes)", value, what));
      }
    }
    toml::table t;
    t.insert("v", std::string(value));
    return t;
  }

  void apply(toml::table& root) {
    const std::size_t eq = text_.find('=');
    if (eq == std::string::npos) fail("expected KEY=VALUE, e.g. fluid.c0=40");
    // KEY+=VALUE appends to the array KEY (the elements of an array value, or the value).
    const bool append = eq > 0 && text_[eq - 1] == '+';
    const std::string_view key = trim(std::string_view(text_).substr(0, append ? eq - 1 : eq));
    const std::string_view value = trim(std::string_view(text_).substr(eq + 1));
    const std::vector<Segment> path = parse_key(key);
    if (path.empty())
      fail(fmt::format("'{}' is not a key path (names separated by dots, an index in brackets: fluid.block[0].min)",
                       key));
    if (value.empty()) fail("no value after '='");
    toml::table parsed = parse_value(value);
    toml::node& v = *parsed.get("v");

    toml::table* table = &root;
    std::string where;
    for (std::size_t k = 0; k < path.size(); ++k) {
      const Segment& s = path[k];
      const bool last = k + 1 == path.size();
      where += (where.empty() ? "" : ".") + s.name;
      if (!s.index) {
        if (last && append) {
          toml::node* n = table->get(s.name);
          if (!n) n = table->insert(s.name, toml::array{}).first->second.as_array();
          toml::array* a = n->as_array();
          if (!a) fail(fmt::format("{} is {}; += appends to an array", where, kind_of(*n)));
          if (toml::array* values = v.as_array())
            for (toml::node& e : *values) put(*a, a->size(), e);
          else
            put(*a, a->size(), v);
          return;
        }
        if (last) {
          put(*table, s.name, v);
          return;
        }
        toml::node* n = table->get(s.name);
        if (!n) n = table->insert(s.name, toml::table{}).first->second.as_table();
        if (n->is_array_of_tables())
          fail(fmt::format("{} is an array of tables ([[{}]]); give an index: {}[0]", where, where, where));
        if (!n->is_table()) fail(fmt::format("{} is {}, not a table", where, kind_of(*n)));
        table = n->as_table();
        continue;
      }
      if (last && append) fail(fmt::format("{}[{}]: += appends to an array: name the array, {}", where, *s.index, where));
      const std::size_t i = *s.index;
      toml::node* n = table->get(s.name);
      if (!n) {
        if (i != 0) fail(fmt::format("the scene has no {}; only {}[0] can start it", where, where));
        n = table->insert(s.name, toml::array{}).first->second.as_array();
      }
      toml::array* a = n->as_array();
      if (!a) fail(fmt::format("{} is {}, not an array", where, kind_of(*n)));
      if (i > a->size())
        fail(fmt::format("{}[{}]: the scene has {} ({}[0] .. {}[{}]; {}[{}] appends one)", where, i, a->size(), where,
                         where, a->size() == 0 ? 0 : a->size() - 1, where, a->size()));
      where += fmt::format("[{}]", i);
      if (last) {
        put(*a, i, v);
        return;
      }
      if (i == a->size()) a->push_back(toml::table{});
      toml::node* element = a->get(i);
      if (!element->is_table()) fail(fmt::format("{} is {}, not a table", where, kind_of(*element)));
      table = element->as_table();
    }
  }

 private:
  // toml++ stores concrete node types: visit gives the value's own type.
  static void put(toml::table& t, const std::string& key, toml::node& v) {
    v.visit([&](auto& concrete) { t.insert_or_assign(key, std::move(concrete)); });
  }
  static void put(toml::array& a, std::size_t i, toml::node& v) {
    v.visit([&](auto& concrete) {
      if (i == a.size()) a.push_back(std::move(concrete));
      else a.replace(a.cbegin() + static_cast<std::ptrdiff_t>(i), std::move(concrete));
    });
  }

  const std::string& file_;
  const std::string& text_;
};

}  // namespace

void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, const std::string& file) {
  for (const std::string& text : overrides) Applier(file, text).apply(root);
}

}  // namespace bw::scene
