// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/write_skeleton.h"

#include <fstream>
#include <iomanip>

#include "subfab/core/error.h"

namespace subfab {

void write_skeleton(const Skeleton& skeleton, std::ostream& out) {
  out << "ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n" << skeleton.num_nodes() << "\n";
  out << std::setprecision(17);
  for (std::size_t v = 0; v < skeleton.num_nodes(); ++v) {
    const Vec3& p = skeleton.points[v];
    out << v << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << skeleton.radii[v] << ' '
        << skeleton.neighbors[v].size();
    for (int w : skeleton.neighbors[v]) out << ' ' << w;
    out << '\n';
  }
}

void write_skeleton(const Skeleton& skeleton, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw IoError("cannot write " + path.string() + ": check the folder exists and is writable");
  write_skeleton(skeleton, out);
  if (!out) throw IoError("error while writing " + path.string());
}

}  // namespace subfab
