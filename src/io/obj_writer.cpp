#include "fastcorot/io/obj_writer.h"

#include "fastcorot/core/error.h"
#include "fastcorot/io/atomic_file.h"

#include <ostream>

namespace fastcorot {

void write_obj(const std::filesystem::path& path, std::span<const Vec3<double>> points,
               std::span<const Triangle> triangles, const std::string& title) {
  const auto count = static_cast<Index>(points.size());
  for (const Triangle& t : triangles) {
    for (Index v : t) {
      if (v < 0 || v >= count) {
        throw make_error(path.string(), ": a triangle names point ", v, " of a surface of ", count, " points");
      }
    }
  }
  write_stream_atomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << "# " << title << " (fastcorot)\n";
    for (const auto& p : points) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (const Triangle& t : triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  });
}

}  // namespace fastcorot
