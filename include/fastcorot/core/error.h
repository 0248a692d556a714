// The one exception type of fastcorot. Every check on user input (files, scenes, parameters,
// meshes) throws `fastcorot::Error` with a message that names what is wrong and where: the file and
// line, the object, the attribute, or the element index. Front ends print the message and exit
// with status 2.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace fastcorot {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Builds a message from streamable pieces: `throw make_error("tetrahedron ", t, " has volume ", v);`
template <class... Parts>
Error make_error(Parts&&... parts) {
  std::ostringstream out;
  out.precision(17);
  (out << ... << std::forward<Parts>(parts));
  return Error(out.str());
}

// `error` placed at `where` ("file:line: Type"): "where: message", unless the message already
// starts there (an inner check that named the same place).
inline Error error_at(const std::string& where, const Error& error) {
  const std::string message = error.what();
  if (message.starts_with(where)) return error;
  return Error(where + ": " + message);
}

}  // namespace fastcorot
