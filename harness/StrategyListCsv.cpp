#include "harness/StrategyListCsv.h"

#include "harness/CsvText.h"

namespace cdb {

namespace {

const char* kindName(StrategyRegistry::Kind kind) {
  switch (kind) {
    case StrategyRegistry::Kind::ImageBased: return "image-based";
    case StrategyRegistry::Kind::Reference: return "reference";
    case StrategyRegistry::Kind::CpuPeer: return "cpu-peer";
  }
  return "unknown";
}

}  // namespace

void writeStrategiesCsv(std::ostream& out, const StrategyRegistry& registry) {
  out << "name,kind,description\n";
  for (const auto& name : registry.names())
    out << name << ',' << kindName(registry.kind(name)) << ',' << csvQuoted(registry.description(name))
        << '\n';
}

}  // namespace cdb
