"""The thesis' Tables 4.1-4.3 (results/thesis/tables.csv), looked up cell by cell."""

from pathlib import Path

from .runs import STATISTICS
from .tabular import InputError, read_typed_csv

DEFAULT_PATH = Path(__file__).resolve().parents[2] / "results" / "thesis" / "tables.csv"
THESIS_HARDWARE = "GeForce 6800, Pentium 4 3.0 GHz"

TABLE_OF = {"env1": "4.1", "env2": "4.2", "env3": "4.3"}

# Strategies the thesis names as what it compares against but gives no numbers for in Tables 4.1-4.3
# (Quick-CULLIDE: Chapters 1 and 2 only). Their rows show this run alone, and the report says why.
NAMED_WITHOUT_NUMBERS = {"quick_cullide": "Quick-CULLIDE"}


class ThesisTables:
    def __init__(self, path: Path):
        self.path = path
        rows = read_typed_csv(path, ("environment", "statistic", "strategy", "resolution", "objects",
                                     "cd_time_ms"), ("resolution", "objects"), ("cd_time_ms",),
                              choices={"statistic": STATISTICS})
        self._values = {}
        self._tables = {}
        for r in rows:
            key = (r["environment"], r["statistic"], r["strategy"], r["resolution"], r["objects"])
            if key in self._values:
                raise InputError(f"{path}: cell {key} appears twice")
            self._values[key] = r["cd_time_ms"]
            if r.get("table"):
                self._tables[r["environment"]] = r["table"]

    def value(self, environment, statistic, strategy, resolution, objects):
        """The thesis' number for exactly this cell, or None: a neighbouring cell is never substituted."""
        return self._values.get((environment, statistic, strategy, resolution, objects))

    def table_name(self, environment):
        return self._tables.get(environment) or TABLE_OF.get(environment)

    def strategies(self, environment):
        return {k[2] for k in self._values if k[0] == environment}

    def values_of(self, environment, dimension):
        """Distinct resolutions (dimension 'resolution') or object counts ('objects') of an environment."""
        index = 3 if dimension == "resolution" else 4
        return sorted({k[index] for k in self._values if k[0] == environment})

    def swept_dimension(self, environment):
        """'objects' for a table over object counts (4.3), 'resolution' for one over resolutions, None if absent."""
        if not any(k[0] == environment for k in self._values):
            return None
        if len(self.values_of(environment, "objects")) > 1 and len(self.values_of(environment, "resolution")) == 1:
            return "objects"
        return "resolution"
