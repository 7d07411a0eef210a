#include "scene/output.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <png.h>

#include <Eigen/Geometry>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

void writeParticlesPly(const std::filesystem::path& path, const Fluid& f, double particleVolume,
                       double time) {
  writeAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\n";
    out << "comment time_s " << std::setprecision(17) << time << "\n";
    out << "comment y_up\n";
    out << "element vertex " << f.size() << "\n";
    for (const char* name : {"x", "y", "z", "vx", "vy", "vz", "c"})
      out << "property float " << name << "\n";
    out << "end_header\n";
    for (size_t i = 0; i < f.size(); ++i) {
      float row[7] = {f.x[i].x(), f.x[i].y(), f.x[i].z(), f.v[i].x(),
                      f.v[i].y(), f.v[i].z(), float(f.sed[i] / particleVolume)};
      out.write(reinterpret_cast<const char*>(row), sizeof row);  // x86-64 is little-endian
    }
  });
}

namespace {

// Writes an image through libpng into the stream: 16-bit grey (channels 1, depth 16) or 8-bit RGB.
void writePng(std::ostream& out, int width, int height, int channels, int depth,
              const std::vector<unsigned char>& rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw std::runtime_error("libpng: out of memory");
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng failed to encode the image");
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, png_size_t len) {
        static_cast<std::ostream*>(png_get_io_ptr(p))->write(reinterpret_cast<char*>(data), len);
      },
      [](png_structp p) { static_cast<std::ostream*>(png_get_io_ptr(p))->flush(); });
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), depth,
               channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (depth == 16) png_set_swap(png);  // our samples are little-endian; PNG is big-endian
  const size_t stride = size_t(width) * channels * (depth / 8);
  for (int r = 0; r < height; ++r)
    png_write_row(png, const_cast<png_bytep>(rows.data() + size_t(r) * stride));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace

std::pair<double, double> writeHeightPng16(const std::filesystem::path& path,
                                           const Heightfield& hf) {
  const double lo = hf.minHeight(), hi = hf.maxHeight(), range = hi > lo ? hi - lo : 1.0;
  std::vector<unsigned char> rows(size_t(hf.nx()) * hf.nz() * 2);
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i) {
      auto v = uint16_t(std::lround((hf.at(i, k) - lo) / range * 65535.0));
      std::memcpy(&rows[(size_t(k) * hf.nx() + i) * 2], &v, 2);
    }
  writeAtomically(path, [&](std::ostream& out) { writePng(out, hf.nx(), hf.nz(), 1, 16, rows); });
  return {lo, hi};
}

double writeMapPng16(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& values) {
  double top = 0.0;
  for (double v : values) top = std::max(top, v);
  std::vector<unsigned char> rows(size_t(nx) * nz * 2, 0);
  if (top > 0)
    for (size_t k = 0; k < values.size(); ++k) {
      const auto v = uint16_t(std::lround(std::clamp(values[k] / top, 0.0, 1.0) * 65535.0));
      std::memcpy(&rows[k * 2], &v, 2);
    }
  writeAtomically(path, [&](std::ostream& out) { writePng(out, nx, nz, 1, 16, rows); });
  return top;
}

void writeDirectionPng16(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& x,
                         const std::vector<double>& z) {
  std::vector<unsigned char> rows(size_t(nx) * nz * 6, 0);
  auto level = [](double c) { return uint16_t(std::lround((std::clamp(c, -1.0, 1.0) + 1.0) * 0.5 * 65535.0)); };
  for (size_t k = 0; k < x.size(); ++k) {
    const uint16_t rgb[3] = {level(x[k]), level(z[k]), uint16_t(x[k] != 0.0 || z[k] != 0.0 ? 65535 : 0)};
    std::memcpy(&rows[k * 6], rgb, 6);
  }
  writeAtomically(path, [&](std::ostream& out) { writePng(out, nx, nz, 3, 16, rows); });
}

std::pair<double, double> writeHeightR16(const std::filesystem::path& path, const Heightfield& hf) {
  const double lo = hf.minHeight(), hi = hf.maxHeight(), range = hi > lo ? hi - lo : 1.0;
  writeAtomically(path, [&](std::ostream& out) {
    for (double h : hf.heights()) {
      const auto v = uint16_t(std::lround((h - lo) / range * 65535.0));
      const unsigned char le[2] = {static_cast<unsigned char>(v & 0xff), static_cast<unsigned char>(v >> 8)};
      out.write(reinterpret_cast<const char*>(le), 2);
    }
  });
  return {lo, hi};
}

void writeGridExr(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& values) {
  writeGridExr(path, nx, nz, {{"Y", &values}});
}

void writeGridExr(const std::filesystem::path& path, int nx, int nz,
                  const std::vector<std::pair<std::string, const std::vector<double>*>>& channels) {
  std::vector<std::vector<float>> px;
  for (const auto& c : channels) px.emplace_back(c.second->begin(), c.second->end());
  Imf::StdOSStream stream;
  try {
    Imf::Header header(nx, nz);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& c : channels) header.channels().insert(c.first, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < channels.size(); ++c)
      fb.insert(channels[c].first, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px[c].data()), sizeof(float), size_t(nx) * sizeof(float)));
    file.setFrameBuffer(fb);
    file.writePixels(nz);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": cannot write the EXR image: " + e.what());
  }
  const std::string bytes = stream.str();
  writeAtomically(path, [&](std::ostream& out) { out << bytes; });
}

void writeHeightRaw(const std::filesystem::path& path, const Heightfield& hf) {
  writeAtomically(path, [&](std::ostream& out) {
    for (double h : hf.heights()) {
      float v = float(h);
      out.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  });
}

void writeTerrainObj(const std::filesystem::path& path, const Heightfield& hf) {
  const int nx = hf.nx(), nz = hf.nz();
  std::vector<Eigen::Vector3d> normal(size_t(nx) * nz, Eigen::Vector3d::Zero());
  for (int t = 0; t < hf.triangleCount(); ++t) {
    auto c = hf.triangleCorners(t);
    Eigen::Vector3d n = (c[2] - c[0]).cross(c[1] - c[0]);  // |n| = 2 × area, pointing up
    for (auto [i, k] : hf.triangleVertices(t)) normal[size_t(k) * nx + i] += n;
  }
  writeAtomically(path, [&](std::ostream& out) {
    out << "# Scour terrain, " << nx << " x " << nz << " vertices, y up\n" << std::setprecision(9);
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i)
        out << "v " << hf.x0() + i * hf.dx() << " " << hf.at(i, k) << " " << hf.z0() + k * hf.dz() << "\n";
    for (const Eigen::Vector3d& n : normal) {
      Eigen::Vector3d u = n.normalized();
      out << "vn " << u.x() << " " << u.y() << " " << u.z() << "\n";
    }
    for (int t = 0; t < hf.triangleCount(); ++t) {
      auto v = hf.triangleVertices(t);
      // Engine order is clockwise seen from above (+y); OBJ wants counter-clockwise.
      const int order[3] = {0, 2, 1};
      out << "f";
      for (int a : order) {
        const long id = long(v[a][1]) * nx + v[a][0] + 1;
        out << " " << id << "//" << id;
      }
      out << "\n";
    }
  });
}

double writeErosionPng(const std::filesystem::path& path, const Heightfield& hf,
                       const std::vector<double>& change) {
  double scale = 0;
  for (double d : change) scale = std::max(scale, std::abs(d));
  std::vector<unsigned char> rows(size_t(hf.nx()) * hf.nz() * 3);
  for (size_t v = 0; v < change.size(); ++v) {
    const double t = scale > 0 ? std::min(std::abs(change[v]) / scale, 1.0) : 0.0;
    const auto fade = static_cast<unsigned char>(std::lround(255.0 * (1.0 - t)));
    unsigned char* px = &rows[v * 3];
    if (change[v] < 0) px[0] = 255, px[1] = fade, px[2] = fade;       // erosion: red
    else if (change[v] > 0) px[0] = fade, px[1] = fade, px[2] = 255;  // deposition: blue
    else px[0] = px[1] = px[2] = 255;
  }
  writeAtomically(path, [&](std::ostream& out) { writePng(out, hf.nx(), hf.nz(), 3, 8, rows); });
  return scale;
}

}  // namespace scour
