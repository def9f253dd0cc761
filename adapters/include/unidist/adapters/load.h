// Model loading for the command line and the plugins: a primitive spec or a model file, chosen by the text.
// File formats are looked up by extension in one table (modelFormats()); a reader for a new format is one
// entry there (adapters/src/load.cpp) and nothing else changes.
#pragma once

#include "unidist/model.h"

#include <memory>
#include <string>
#include <vector>

namespace unidist {

/// Reads one model file; throws InputError naming the file and the line or byte offset of the problem.
using ModelReader = std::shared_ptr<const Model> (*)(const std::string& path);

/// One known file format. `read` is null while the format is recognised but has no reader yet.
struct ModelFormat {
  const char* extension;  ///< lower case with the dot, e.g. ".obj"; matched case-insensitively, longest first
  const char* name;       ///< for messages, e.g. "OBJ"
  ModelReader read;
};

/// Every format loadModel recognises, in the order of the contract.
const std::vector<ModelFormat>& modelFormats();

/// The format a file name's extension selects (case-insensitive, the longest matching extension), or null.
const ModelFormat* findModelFormat(const std::string& path);

/// A primitive spec when the text looks like `name:key=value,...` (looksLikePrimitiveSpec), otherwise a file
/// path: a missing or unreadable file, an unknown extension or a format without a reader throws InputError
/// naming the file.
std::shared_ptr<const Model> loadModel(const std::string& specOrPath);

}  // namespace unidist
