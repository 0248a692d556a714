// Writing triangle surfaces as Wavefront OBJ (`fastcorot run --obj`: the visual surfaces, or an
// object's boundary, per frame), written atomically (atomic_file.h). Positions are printed with
// 17 significant digits, so that reading the file back gives the same doubles.
#pragma once

#include "fastcorot/core/types.h"

#include <filesystem>
#include <span>
#include <string>

namespace fastcorot {

// A comment line naming `title`, one `v x y z` per point and one `f a b c` per triangle (1-based,
// as OBJ counts). Throws fastcorot::Error naming the file when a triangle names a point outside
// [0, points.size()) or writing fails.
void write_obj(const std::filesystem::path& path, std::span<const Vec3<double>> points,
               std::span<const Triangle> triangles, const std::string& title);

}  // namespace fastcorot
