// loadModel: a primitive spec or a file, the file format chosen by extension from kFormats. A format's reader
// is one entry of that table: mesh (OBJ/STL/PLY), point-cloud (XYZ/PLY) and NURBS (.unurbs.json, IGES)
// readers plug in there as they arrive.
#include "unidist/adapters/load.h"
#include "unidist/adapters/spec.h"

#include "extent_check.h"
#include "formats/readers.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace unidist {
namespace {

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Throws unless path names a regular file we can open for reading.
void requireReadableFile(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw InputError(path + ": is a directory, not a model file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    const int err = errno;
    throw InputError(path + ": cannot open (" + std::strerror(err) + ")");
  }
  std::fclose(f);
}

}  // namespace

const std::vector<ModelFormat>& modelFormats() {
  // Readers arrive with their issues; until then a recognised format says so instead of guessing.
  static const std::vector<ModelFormat> kFormats = {
      {".obj", "OBJ", &formats::readObj},
      {".stl", "STL", &formats::readStl},
      {".ply", "PLY", &formats::readPly},
      {".xyz", "XYZ point cloud", &formats::readXyz},
      {".unurbs.json", "unidist NURBS (.unurbs.json)", &formats::readUnurbs},
      {".igs", "IGES", &formats::readIges},
      {".iges", "IGES", &formats::readIges},
  };
  return kFormats;
}

const ModelFormat* findModelFormat(const std::string& path) {
  const std::string lower = lowerCase(std::filesystem::path(path).filename().string());
  const ModelFormat* format = nullptr;
  for (const ModelFormat& f : modelFormats())
    if (endsWith(lower, f.extension) && (!format || std::strlen(f.extension) > std::strlen(format->extension)))
      format = &f;
  return format;
}

std::shared_ptr<const Model> loadModel(const std::string& specOrPath) {
  if (looksLikePrimitiveSpec(specOrPath)) return parsePrimitiveSpec(specOrPath);
  if (specOrPath.empty()) throw InputError("empty model argument (expected a primitive spec or a file)");
  requireReadableFile(specOrPath);

  const ModelFormat* format = findModelFormat(specOrPath);
  if (!format) {
    std::string known;
    for (const ModelFormat& f : modelFormats()) known += std::string(known.empty() ? "" : " ") + f.extension;
    throw InputError(specOrPath + ": unknown model format (known extensions: " + known +
                     "; primitive specs look like sphere:r=1)");
  }
  if (!format->read) throw InputError(specOrPath + ": " + format->name + " files are not supported yet");
  std::shared_ptr<const Model> model = format->read(specOrPath);
  requireFiniteExtent(*model, specOrPath);
  return model;
}

}  // namespace unidist
