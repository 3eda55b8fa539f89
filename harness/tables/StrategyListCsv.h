#pragma once
// `cdbench strategies --csv`: every registered detector with its kind, for tools that must know
// them (the report's display order and colours are checked against it).
#include <ostream>

#include "culling/DetectorRegistry.h"

namespace cdb {

// Columns name, kind (image-based, reference, cpu-peer), description; in registration order.
void writeStrategiesCsv(std::ostream& out, const DetectorRegistry& registry);

}  // namespace cdb
