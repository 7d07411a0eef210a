#pragma once
// Elevation data through GDAL (docs/exports.md): GeoTIFF, SRTM .hgt, ASCII grid and the other
// rasters GDAL reads come in as heightmaps with their NoData holes filled and their georeference
// kept; heights and maps go out as float32 GeoTIFF carrying that georeference.
//
// Georeference: GDAL's affine geotransform g, the pixel (column c, row r) corner at
//   X = g0 + c g1 + r g2,  Y = g3 + c g4 + r g5,
// and the coordinate system as WKT. A heightmap's pixel centres are its samples (the bilinear
// resampling onto the grid takes pixel p at u = p), so vertex (i, k) of the grid lies at the
// centre of output pixel (i, k), and the output geotransform is the input's with its pixels
// stretched by (crop − 1) / (n − 1).

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "scene/presets.h"

namespace scour {

struct Georeference {
  bool valid = false;                 ///< false: the file had none (or it is not a GDAL raster)
  std::array<double, 6> transform{};  ///< GDAL geotransform of the pixel corners
  std::string crs;                    ///< coordinate system, WKT ("" when the file names none)
};

/// A raster read through GDAL: its first band as doubles, row-major (row r along +z).
struct GeoRaster {
  int width = 0, height = 0;
  std::vector<double> values;
  Georeference georeference;
  long long filled = 0;    ///< NoData (or non-finite) pixels filled
  bool hasNoData = false;  ///< the band declares a NoData value
  double noData = 0;       ///< that value
};

/// Whether `file` is read through GDAL (by its ending: .tif, .tiff, .hgt, .asc, .dem, .bil,
/// .img, .grd, any case).
bool isGdalRaster(const std::string& file);

/// Reads band 1 of `file` (TerrainError with GDAL's reason when it cannot). NoData pixels (the
/// band's NoData value, and any non-finite value) are filled as gdal_fillnodata does:
/// GDALFillNodata, inverse-distance weighting of the nearest valid pixels found in four
/// directions, searched across the whole image, no smoothing. A raster with no valid pixel is
/// refused.
GeoRaster readGeoRaster(const std::string& file);

/// The georeference of a heightmap terrain's grid of nx × nz vertices: its file's, with the crop
/// and the resampling applied (invalid when the file has none or is not a GDAL raster).
Georeference gridGeoreference(const TerrainSpec& t, int nx, int nz);

/// The georeference of a grid whose vertex (i, k) lies at the centre of `in`'s pixel
/// (firstX + i sx, firstZ + k sz): each output pixel spans half a step of the grid on either side
/// of its vertex. Cropping and resampling a heightmap, and resampling a grid (--resample), alike.
Georeference resampledGeoreference(const Georeference& in, double firstX, double firstZ, double sx, double sz);

/// A local georeference for a grid with no input one: x to the right, z down the rows, in metres
/// from the grid's origin (no coordinate system).
Georeference localGeoreference(double x0, double z0, double dx, double dz);

/// Writes float32 bands (each nx × nz, row k the grid's row k) as a GeoTIFF (deflate) with the
/// georeference, the band unit and metadata items, through writeAtomically.
void writeGeoTiff(const std::filesystem::path& path, int nx, int nz,
                  const std::vector<const std::vector<double>*>& bands, const Georeference& g,
                  const std::string& unit, const std::map<std::string, std::string>& metadata);

}  // namespace scour
