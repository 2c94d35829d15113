// Small formatting helpers for messages and summaries.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace bw {

// "512 B", "3.2 KiB", "1.5 GiB".
std::string human_bytes(std::uint64_t bytes);
// "12.3 s", "4 min 05 s", "2 h 03 min".
std::string human_duration(double seconds);
// "1.25 M", "730 k", "12"; from 1e12 on, "2.7e+16".
std::string human_count(double count);
// JSON string literal with quotes and escapes.
std::string json_quote(std::string_view text);

// The whole of a text file given by a user, such as a scene. Throws InputError naming
// `path` when it does not exist, is a folder (`kind` says what was expected: "a scene
// file"), cannot be read or is binary (an HDF5 file, say).
std::string read_text_file(const std::string& path, const std::string& kind);

// The pieces of `text` between the separators, empty ones included ("a::b" gives
// "a", "", "b"; "" gives one empty piece).
std::vector<std::string> split(const std::string& text, char separator);

}  // namespace bw
