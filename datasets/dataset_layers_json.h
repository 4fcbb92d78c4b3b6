#pragma once
// dataset.json's layer objects ↔ DatasetMeta (format in dataset_format.cpp): "imagery" with its
// radiometry and deshading record, "ndvi", "landcover" and "canopy". For dataset_format.cpp.

#include <nlohmann/json.hpp>

#include "core/result.h"
#include "datasets/dataset_field_reader.h"
#include "datasets/dataset_format.h"

namespace vegstream::datasets::dataset_json {

// The extension of an imagery tile's file: "jpg" or "png".
const char* imageryExtension(ImageryFormat f);

// Each layer's object (not null) into m; errors name f's source and the field.
Status parseImagery(const json& im, const FieldReader& f, DatasetMeta& m);
Status parseNdvi(const json& nd, const FieldReader& f, DatasetMeta& m);
Status parseLandcover(const json& lc, const FieldReader& f, DatasetMeta& m);
Status parseCanopy(const json& c, const FieldReader& f, DatasetMeta& m);

// Each layer's object, or null when m has no such layer.
json imageryJson(const DatasetMeta& m);
json ndviJson(const DatasetMeta& m);
json landcoverJson(const DatasetMeta& m);
json canopyJson(const DatasetMeta& m);

}  // namespace vegstream::datasets::dataset_json
