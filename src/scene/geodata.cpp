#include "scene/geodata.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <memory>
#include <mutex>

#include "scene/heightmap_size.h"
#include "scene/input_file.h"
#include "scene/output.h"

namespace scour {

namespace {

void registerDrivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// GDAL's messages go to the exception, not to stderr; the last one is the reason.
struct QuietErrors {
  QuietErrors() { CPLPushErrorHandler(CPLQuietErrorHandler), CPLErrorReset(); }
  ~QuietErrors() { CPLPopErrorHandler(); }
  static std::string reason() {
    const std::string m = CPLGetLastErrorMsg();
    return m.empty() ? "no reason given" : m;
  }
};

struct DatasetCloser {
  void operator()(void* d) const {
    if (d) GDALClose(GDALDatasetH(d));
  }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

Dataset openRaster(const std::string& file) {
  registerDrivers();
  const char* const drivers[] = {"GTiff", "SRTMHGT", "AAIGrid", "USGSDEM", "EHdr", "HFA", "GSAG", "GS7BG", "GSBG", nullptr};
  Dataset d(GDALOpenEx(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr));
  if (!d) throw TerrainError(file + ": GDAL cannot read it as elevation data (" + QuietErrors::reason() + ")");
  return d;
}

Georeference georeferenceOf(GDALDatasetH d) {
  Georeference g;
  g.valid = GDALGetGeoTransform(d, g.transform.data()) == CE_None;
  const char* wkt = GDALGetProjectionRef(d);
  g.crs = wkt ? wkt : "";
  return g;
}

}  // namespace

bool isGdalRaster(const std::string& file) {
  const size_t dot = file.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = file.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* e : {"tif", "tiff", "hgt", "asc", "dem", "bil", "img", "grd"})
    if (ext == e) return true;
  return false;
}

GeoRaster readGeoRaster(const std::string& file) {
  size_t bytes = 0;
  try {
    bytes = checkInputFile(file, "heightmap", size_t(1) << 32);
  } catch (const InputFileError& e) {
    throw TerrainError(e.what());
  }
  QuietErrors quiet;
  Dataset d = openRaster(file);
  GDALDatasetH ds = GDALDatasetH(d.get());
  GeoRaster r;
  r.width = GDALGetRasterXSize(ds), r.height = GDALGetRasterYSize(ds);
  const long long w = r.width, h = r.height;
  const int bands = GDALGetRasterCount(ds);
  if (bands < 1) throw TerrainError(file + ": holds no raster band");
  {
    // GDAL decodes a whole block to read one band of it, and a pixel-interleaved block holds every
    // band: a file of tens of thousands of bands in 256 × 256 blocks asks for gigabytes to read the
    // first (found by the fuzzer). Scour reads band 1; a block bigger than this is refused.
    constexpr double kMaxBlockBytes = double(size_t(1) << 30);
    GDALRasterBandH first = GDALGetRasterBand(ds, 1);
    int bx = 0, by = 0;
    GDALGetBlockSize(first, &bx, &by);
    const char* interleave = GDALGetMetadataItem(ds, "INTERLEAVE", "IMAGE_STRUCTURE");
    const bool pixel = interleave && std::string(interleave) == "PIXEL";
    const double block = double(bx) * double(by) * double(GDALGetDataTypeSizeBytes(GDALGetRasterDataType(first))) *
                         (pixel ? double(bands) : 1.0);
    if (block > kMaxBlockBytes)
      throw TerrainError(file + ": " + std::to_string(bands) + " bands in blocks of " + std::to_string(bx) + " x " +
                         std::to_string(by) + " pixels: reading the first needs " +
                         std::to_string(static_cast<long long>(block / 1048576.0)) + " MiB (at most 1024)");
  }
  checkHeightmapSize(file, w, h, double(std::max<size_t>(bytes, 1)), "raster", "the file");
  r.georeference = georeferenceOf(ds);
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  int has = 0;
  const double noData = GDALGetRasterNoDataValue(band, &has);
  r.hasNoData = has != 0, r.noData = noData;
  r.values.resize(size_t(w) * size_t(h));
  if (GDALRasterIO(band, GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height, GDT_Float64, 0, 0) != CE_None)
    throw TerrainError(file + ": GDAL cannot read its pixels (" + QuietErrors::reason() + ")");
  auto missing = [&](double v) { return !std::isfinite(v) || (r.hasNoData && v == noData); };
  r.filled = std::count_if(r.values.begin(), r.values.end(), missing);
  if (r.filled == w * h)
    throw TerrainError(file + ": holds no data (every pixel is NoData" +
                       (r.hasNoData ? " (" + std::to_string(noData) + ")" : std::string()) + ")");
  if (r.filled == 0) return r;
  // gdal_fillnodata on a copy in memory: the holes carry a NaN NoData, searched across the image.
  GDALDriverH mem = GDALGetDriverByName("MEM");
  Dataset copy(mem ? GDALCreate(mem, "", r.width, r.height, 1, GDT_Float64, nullptr) : nullptr);
  if (!copy) throw TerrainError(file + ": cannot make room to fill its NoData (" + QuietErrors::reason() + ")");
  GDALRasterBandH work = GDALGetRasterBand(GDALDatasetH(copy.get()), 1);
  std::vector<double> holes = r.values;
  for (double& v : holes)
    if (missing(v)) v = NAN;
  GDALSetRasterNoDataValue(work, NAN);
  const double reach = double(std::max(r.width, r.height));
  if (GDALRasterIO(work, GF_Write, 0, 0, r.width, r.height, holes.data(), r.width, r.height, GDT_Float64, 0, 0) != CE_None ||
      GDALFillNodata(work, nullptr, reach, 0, 0, nullptr, nullptr, nullptr) != CE_None ||
      GDALRasterIO(work, GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height, GDT_Float64, 0, 0) != CE_None)
    throw TerrainError(file + ": GDAL cannot fill its NoData (" + QuietErrors::reason() + ")");
  const long long left = std::count_if(r.values.begin(), r.values.end(), [](double v) { return !std::isfinite(v); });
  if (left > 0)
    throw TerrainError(file + ": " + std::to_string(left) + " NoData pixels are left after filling");
  return r;
}

Georeference gridGeoreference(const TerrainSpec& t, int nx, int nz) {
  if (t.kind != "heightmap" || !isGdalRaster(t.file)) return {};
  QuietErrors quiet;
  Dataset d = openRaster(t.file);
  GDALDatasetH ds = GDALDatasetH(d.get());
  Georeference in = georeferenceOf(ds);
  if (!in.valid) return in;
  const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
  const int cw = t.crop_w > 0 ? t.crop_w : w - t.crop_x, ch = t.crop_h > 0 ? t.crop_h : h - t.crop_z;
  return resampledGeoreference(in, t.crop_x, t.crop_z, double(cw - 1) / (nx - 1), double(ch - 1) / (nz - 1));
}

Georeference resampledGeoreference(const Georeference& in, double firstX, double firstZ, double sx, double sz) {
  const double cx = firstX + 0.5 - 0.5 * sx, cz = firstZ + 0.5 - 0.5 * sz;
  const auto& g = in.transform;
  Georeference out = in;
  out.transform = {g[0] + g[1] * cx + g[2] * cz, g[1] * sx, g[2] * sz,
                   g[3] + g[4] * cx + g[5] * cz, g[4] * sx, g[5] * sz};
  return out;
}

Georeference localGeoreference(double x0, double z0, double dx, double dz) {
  Georeference g;
  g.valid = true;
  g.transform = {x0 - 0.5 * dx, dx, 0.0, z0 - 0.5 * dz, 0.0, dz};
  return g;
}

void writeGeoTiff(const std::filesystem::path& path, int nx, int nz,
                  const std::vector<const std::vector<double>*>& bands, const Georeference& g,
                  const std::string& unit, const std::map<std::string, std::string>& metadata) {
  registerDrivers();
  QuietErrors quiet;
  static std::atomic<unsigned> counter{0};
  const std::string name = "/vsimem/scour-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".tif";
  // Gone at the end, whatever happens (taking its buffer below removes it already).
  struct MemFile {
    std::string name;
    ~MemFile() { VSIUnlink(name.c_str()); }
  } file{name};
  auto fail = [&](const std::string& what) {
    throw std::runtime_error("cannot write " + path.string() + ": " + what + " (" + QuietErrors::reason() + ")");
  };
  {
    GDALDriverH tiff = GDALGetDriverByName("GTiff");
    if (!tiff) fail("GDAL has no GeoTIFF driver");
    char** options = nullptr;
    options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
    options = CSLSetNameValue(options, "PREDICTOR", "3");
    options = CSLSetNameValue(options, "TILED", "YES");
    Dataset d(GDALCreate(tiff, name.c_str(), nx, nz, int(bands.size()), GDT_Float32, options));
    CSLDestroy(options);
    if (!d) fail("GDAL cannot create the GeoTIFF");
    GDALDatasetH ds = GDALDatasetH(d.get());
    if (g.valid) GDALSetGeoTransform(ds, const_cast<double*>(g.transform.data()));
    if (!g.crs.empty()) GDALSetProjection(ds, g.crs.c_str());
    for (const auto& [key, value] : metadata) GDALSetMetadataItem(ds, key.c_str(), value.c_str(), nullptr);
    std::vector<float> px(size_t(nx) * size_t(nz));
    for (size_t b = 0; b < bands.size(); ++b) {
      std::transform(bands[b]->begin(), bands[b]->end(), px.begin(), [](double v) { return float(v); });
      GDALRasterBandH band = GDALGetRasterBand(ds, int(b) + 1);
      GDALSetRasterUnitType(band, unit.c_str());
      if (GDALRasterIO(band, GF_Write, 0, 0, nx, nz, px.data(), nx, nz, GDT_Float32, 0, 0) != CE_None)
        fail("GDAL cannot write its pixels");
    }
  }  // closed: the file is complete in memory
  vsi_l_offset length = 0;
  GByte* data = VSIGetMemFileBuffer(name.c_str(), &length, TRUE);
  if (!data) fail("GDAL lost the GeoTIFF it wrote");
  std::unique_ptr<GByte, decltype(&VSIFree)> owned(data, &VSIFree);
  writeAtomically(path, [&](std::ostream& out) { out.write(reinterpret_cast<const char*>(data), std::streamsize(length)); });
}

}  // namespace scour
