# Type stubs of arcplan.bench: benchmark campaigns (docs/python.md, docs/benchmarks.md).
import os
import pathlib
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

PathLike = Union[str, os.PathLike]

class RunRecord:
    """One run: OMPL's `solved` and the recorded values by metric key."""
    solved: bool
    succeeded: bool
    values: Dict[str, float]
    def value(self, key: str) -> Optional[float]: ...

class Campaign:
    """A finished campaign read back from its benchmark.db."""
    database: pathlib.Path
    runs: Dict[str, Dict[str, List[RunRecord]]]
    families: Dict[str, str]
    settings: Dict[str, Dict[str, Dict[str, str]]]
    metrics: List[Tuple[str, str]]
    experiments: List[Dict[str, Any]]
    ranking: Dict[str, Any]
    def ranking_table(self) -> str: ...

def run(suite: str = "thesis", *, out: PathLike, planners: Optional[Sequence[str]] = None, runs: Optional[int] = None,
        time: Optional[float] = None, budget: Optional[int] = None, vmax: Optional[float] = None, workers: int = 1,
        plots: bool = False, quiet: bool = True, shard: str = "1/1") -> Dict[str, Any]: ...
def read_campaign(path: PathLike) -> Campaign: ...
