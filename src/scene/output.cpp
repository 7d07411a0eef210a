#include "scene/output.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace scour {

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& fill) {
  std::filesystem::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + path.string() + ": cannot create file");
    fill(out);
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(tmp);
      throw std::runtime_error("cannot write " + path.string() + ": write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("cannot write " + path.string() + ": " + ec.message());
  }
}

void writeParticlesPly(const std::filesystem::path& path, const Fluid& f, double time) {
  writeAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\n";
    out << "comment time_s " << std::setprecision(17) << time << "\n";
    out << "comment y_up\n";
    out << "element vertex " << f.size() << "\n";
    for (const char* name : {"x", "y", "z", "vx", "vy", "vz"})
      out << "property float " << name << "\n";
    out << "end_header\n";
    for (size_t i = 0; i < f.size(); ++i) {
      float row[6] = {f.x[i].x(), f.x[i].y(), f.x[i].z(), f.v[i].x(), f.v[i].y(), f.v[i].z()};
      out.write(reinterpret_cast<const char*>(row), sizeof row);  // x86-64 is little-endian
    }
  });
}

}  // namespace scour
