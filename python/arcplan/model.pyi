# Type stubs of arcplan.model: the model-vs-measurement loop (docs/python.md, docs/model.md).
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
PathLike = Union[str, os.PathLike]

class Effect:
    """An effect entry of a model file: catalogue id (or expression) and joints; str() is 'load_friction:1,2'."""
    id: str
    joints: List[int]
    expressions: List[str]
    explanation: str

def parse_effect(text: str) -> Effect: ...

class Model:
    """A model file: kind, load torque, effects (and fitted parameters)."""
    name: str
    kind: str
    load_torque: str
    effects: List[Effect]
    source: str
    def has_effect(self, id: str) -> bool: ...
    def to_yaml(self) -> str: ...
    def save(self, path: PathLike) -> None: ...

def load_model(path: PathLike) -> Model: ...
def parse_model(text: str, source: PathLike = "model.yaml") -> Model: ...

class Log:
    """A measured log: time (rows,) in s and signals by RTDE name, (rows, joints) or (rows,)."""
    source: str
    time: FloatArray
    rows: int
    joint_count: int
    signals: List[str]
    quality: str
    def signal(self, name: str) -> FloatArray: ...
    def __getitem__(self, name: str) -> FloatArray: ...

def read_log(path: PathLike, *, columns: Optional[str] = None, rows: Optional[str] = None) -> Log: ...
def log_from_arrays(time: npt.ArrayLike, signals: Mapping[str, npt.ArrayLike], source: str = "arrays") -> Log: ...

LogInput = Union[PathLike, Log, Sequence[Union[PathLike, Log]]]

class Data:
    """Logs prepared for a model: the fit data and the optional validation data."""
    channels: List[str]
    samples: int
    validation_samples: Optional[int]
    quality: str

def load_data(model: Model, data: LogInput, validate: Optional[LogInput] = None, *, columns: Optional[str] = None,
              rows: Optional[str] = None, validate_rows: Optional[str] = None) -> Data: ...

class ChannelError:
    channel: str
    rmse: float
    nrmse: float
    r2: float
    samples: int

class ErrorSummary:
    channels: List[ChannelError]
    overall_nrmse: float
    rmse: FloatArray
    nrmse: FloatArray
    r2: FloatArray
    def to_dict(self) -> Dict[str, Any]: ...

class Series:
    """time (samples,); measured, predicted, residual (samples, channels) float64 (gearbox data: lists per channel)."""
    channels: List[str]
    time: FloatArray
    measured: FloatArray
    predicted: FloatArray
    residual: FloatArray

class FittedModel:
    channels: List[str]
    model: Model
    parameters: Dict[str, Any]
    def series(self, validation: bool = False) -> Series: ...

class WorstWindow:
    start: float
    end: float
    nrmse: float
    worst_channel: str

class Event:
    start: float
    end: float
    joints: List[int]
    peak: FloatArray
    peak_scales: float
    wrench: Optional[FloatArray]
    wrench_fit: float

class ResidualCorrelation:
    channel: str
    signal: str
    correlation: float

class Comparison:
    data: ErrorSummary
    validation: Optional[ErrorSummary]
    overall_nrmse: float
    failures_on: str
    worst_windows: List[WorstWindow]
    events: List[Event]
    residual_follows: List[ResidualCorrelation]
    fitted: FittedModel
    series: Series
    validation_series: Optional[Series]
    def to_dict(self) -> Dict[str, Any]: ...

class PhysicalQuantity:
    name: str
    meaning: str
    values: List[float]
    standard_errors: List[float]

class Candidate:
    effect: str
    discovered: bool
    entry: Effect
    model_entry: str
    joints: List[int]
    heldout_reduction: float
    score: float
    suggested: bool
    channel_reduction: FloatArray
    quantities: List[PhysicalQuantity]
    explanation: str

class Diagnosis:
    heldout: str
    heldout_base: ErrorSummary
    ranking: List[Candidate]
    skipped: List[str]
    residual_follows: List[ResidualCorrelation]
    noise_floor: FloatArray
    explainable: float
    catalogue_explains: float
    summary: str
    data_events: List[Event]
    validation_events: List[Event]
    def to_dict(self) -> Dict[str, Any]: ...

class FitStep:
    added: List[str]
    before: ErrorSummary
    after: ErrorSummary
    before_validation: Optional[ErrorSummary]
    after_validation: Optional[ErrorSummary]
    before_fitted: FittedModel
    after_fitted: FittedModel
    model: Model
    def to_dict(self) -> Dict[str, Any]: ...

class HistoryStep:
    command: str
    effects: List[str]
    data: ErrorSummary
    validation: Optional[ErrorSummary]

class History:
    steps: List[HistoryStep]
    overall_nrmse: FloatArray
    validation_overall_nrmse: FloatArray
    def __init__(self) -> None: ...
    @overload
    def add(self, result: Comparison) -> None: ...
    @overload
    def add(self, result: FitStep) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def __len__(self) -> int: ...

def compare(model: Model, data: Data, *, keep_parameters: bool = False,
            session: Optional[PathLike] = None) -> Comparison: ...
def diagnose(model: Model, data: Data, *, folds: int = 5, min_reduction: float = 0.01, keep_parameters: bool = False,
             discovery: bool = True, keep_events: bool = False, candidates: Sequence[str] = ()) -> Diagnosis: ...
def fit(model: Model, data: Data, add: Union[str, Effect, Candidate, Sequence[Union[str, Effect, Candidate]]], *,
        keep_parameters: bool = False, session: Optional[PathLike] = None) -> FitStep: ...
def read_history(session: PathLike) -> History: ...
