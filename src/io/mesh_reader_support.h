// Private helpers shared by the mesh file readers and writers: reading a whole file, a
// bounds-checked cursor over its bytes that reads text tokens and binary values and builds error
// messages naming the file and the line (text) or byte offset (binary), byte-order handling, and
// the final checks every reader applies (finite coordinates, indices in range).
#pragma once

#include "fastcorot/core/error.h"
#include "fastcorot/io/mesh_readers.h"

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace fastcorot::detail {

// The whole file; throws naming the file when it is missing, not a regular file or unreadable.
std::string read_file_bytes(const std::filesystem::path& path);

// 1-based number of the line that holds byte `offset` of `text`.
std::size_t line_number(std::string_view text, std::size_t offset);

// Throws unless every coordinate is finite and every tetrahedron and triangle index lies in
// [0, #points); the message names the file, the element and the index.
void check_mesh_data(const MeshData& mesh, const std::string& file);

// The exact conversion of a count or index read from a file into an Index, or -1 when it does
// not fit.
template <class T>
Index to_index(T value) {
  if constexpr (std::is_signed_v<T>) {
    if (value < 0) return -1;
  }
  if (static_cast<std::uint64_t>(value) > static_cast<std::uint64_t>(INT32_MAX)) return -1;
  return static_cast<Index>(value);
}

template <class T>
T byteswap_value(T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// Reads a T stored at `bytes` (no alignment needed), swapping its bytes when `swap`.
template <class T>
T load_value(const char* bytes, bool swap) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return swap ? byteswap_value(value) : value;
}

inline constexpr bool kHostIsLittleEndian = std::endian::native == std::endian::little;

// A cursor over a file's bytes. Text reads (tokens, lines) report errors as "file:line: ...";
// binary reads report "file: byte N: ...". Every read is bounds-checked: running past the end
// throws "unexpected end of file".
class FileCursor {
 public:
  FileCursor(std::string_view data, std::string file) : data_(data), file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  std::string_view data() const { return data_; }
  std::size_t position() const { return pos_; }
  void set_position(std::size_t pos) { pos_ = pos < data_.size() ? pos : data_.size(); }
  std::size_t remaining() const { return data_.size() - pos_; }
  bool at_end() const { return pos_ >= data_.size(); }

  // Skips spaces, tabs, carriage returns and line breaks; true when something is left.
  bool skip_whitespace() {
    while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
    return pos_ < data_.size();
  }

  // The next whitespace-separated token; `what` names what was expected, for the error message.
  std::string_view token(std::string_view what) {
    if (!skip_whitespace()) fail_text("unexpected end of file, expected ", what);
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    return data_.substr(start, pos_ - start);
  }

  // The next token if one is left on the current line, else an empty view (the cursor stays).
  std::string_view token_on_line() {
    while (pos_ < data_.size() &&
           (data_[pos_] == ' ' || data_[pos_] == '\t' || data_[pos_] == '\r')) {
      ++pos_;
    }
    if (pos_ >= data_.size() || data_[pos_] == '\n') return {};
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    return data_.substr(start, pos_ - start);
  }

  // The rest of the current line without its line break; moves past the break.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    std::size_t end = pos_;
    if (pos_ < data_.size()) ++pos_;
    if (end > start && data_[end - 1] == '\r') --end;
    return data_.substr(start, end - start);
  }

  // Throws unless the next token equals `expected`.
  void expect(std::string_view expected) {
    const std::size_t start = (skip_whitespace(), pos_);
    const std::string_view found = token(expected);
    if (found != expected) {
      pos_ = start;
      fail_text("expected '", expected, "', found '", printable(found), "'");
    }
  }

  template <class T>
  T integer(std::string_view what) {
    static_assert(std::is_integral_v<T>);
    const std::size_t start = (skip_whitespace(), pos_);
    std::string_view text = token(what);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      pos_ = start;
      fail_text("expected an integer (", what, "), found '", printable(text), "'");
    }
    return value;
  }

  double real(std::string_view what) {
    const std::size_t start = (skip_whitespace(), pos_);
    std::string_view text = token(what);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      pos_ = start;
      fail_text("expected a number (", what, "), found '", printable(text), "'");
    }
    return value;
  }

  // The next `count` bytes.
  std::string_view bytes(std::size_t count, std::string_view what) {
    if (count > remaining()) {
      fail_binary("unexpected end of file reading ", what, " (", count, " bytes needed, ",
                  remaining(), " left)");
    }
    const std::string_view out = data_.substr(pos_, count);
    pos_ += count;
    return out;
  }

  template <class T>
  T binary(bool swap, std::string_view what) {
    return load_value<T>(bytes(sizeof(T), what).data(), swap);
  }

  // Moves to just after the next occurrence of `text`; false (cursor at the end) when none.
  bool skip_past(std::string_view text) {
    const std::size_t found = data_.find(text, pos_);
    if (found == std::string_view::npos) {
      pos_ = data_.size();
      return false;
    }
    pos_ = found + text.size();
    return true;
  }

  template <class... Parts>
  [[noreturn]] void fail_text(Parts&&... parts) const {
    throw make_error(file_, ":", line_number(data_, pos_), ": ", std::forward<Parts>(parts)...);
  }

  // As fail_text, for the line that holds byte `offset`.
  template <class... Parts>
  [[noreturn]] void fail_text_at(std::size_t offset, Parts&&... parts) const {
    throw make_error(file_, ":", line_number(data_, offset), ": ", std::forward<Parts>(parts)...);
  }

  template <class... Parts>
  [[noreturn]] void fail_binary(Parts&&... parts) const {
    throw make_error(file_, ": byte ", pos_, ": ", std::forward<Parts>(parts)...);
  }

  // A token shortened and stripped of control bytes, to quote it in a message.
  static std::string printable(std::string_view text) {
    std::string out;
    for (const char c : text.substr(0, 40)) {
      out += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
    }
    if (text.size() > 40) out += "...";
    return out;
  }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v';
  }

  std::string_view data_;
  std::string file_;
  std::size_t pos_ = 0;
};

}  // namespace fastcorot::detail
