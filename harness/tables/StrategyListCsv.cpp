#include "harness/tables/StrategyListCsv.h"

#include "harness/tables/CsvText.h"

namespace cdb {

namespace {

const char* kindName(DetectorRegistry::Kind kind) {
  switch (kind) {
    case DetectorRegistry::Kind::ImageBased: return "image-based";
    case DetectorRegistry::Kind::Reference: return "reference";
    case DetectorRegistry::Kind::CpuPeer: return "cpu-peer";
  }
  return "unknown";
}

}  // namespace

void writeStrategiesCsv(std::ostream& out, const DetectorRegistry& registry) {
  out << "name,kind,description\n";
  for (const auto& name : registry.names())
    out << name << ',' << kindName(registry.kind(name)) << ',' << csvQuoted(registry.description(name))
        << '\n';
}

}  // namespace cdb
