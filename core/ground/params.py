"""The names of the ground methods and engines, and their parameter sets.

Conventions:

* Methods and engines are given by name, never by a position in a list: the method one of
  :data:`METHODS`, the engine one of :data:`ENGINES` (exactly, lower case). Any other value
  raises :class:`~..errors.InputError` naming it and the accepted names.
* A method's parameters are a frozen dataclass (:class:`~.csf.CsfParams`,
  :class:`~.smrf.SmrfParams`) with PDAL's option names and defaults: change one with
  :func:`dataclasses.replace`.
"""
from __future__ import annotations

from typing import Optional, Sequence, Union

from ..errors import InputError
from .csf import CsfParams
from .smrf import SmrfParams

#: The ground methods (PDAL's ``filters.csf`` / ``filters.smrf``), declared once.
METHODS = ("csf", "smrf")
#: The engines: the one measured faster per method (:data:`AUTO_ENGINES`), PDAL only, built-in only.
ENGINES = ("auto", "pdal", "builtin")

#: The engine ``"auto"`` runs for each method: the faster one on bench/bench_ground.py's
#: figures (bench/README.md, "Ground filter: built-in engine against PDAL"). PDAL is then
#: used only when the built-in engine cannot run the method (:func:`.engine.pdal_runner_for`).
AUTO_ENGINES = {"csf": "builtin", "smrf": "builtin"}

Params = Union[CsfParams, SmrfParams]


def _checked_name(value: object, names: Sequence[str], what: str) -> str:
    if isinstance(value, str) and value in names:
        return value
    raise InputError("Unknown {what} {value!r}: expected one of {names}", what=what,
                     value=value, names=", ".join(names))


def method_name(value: object) -> str:
    """``value`` when it is a name of :data:`METHODS`; :class:`InputError` otherwise."""
    return _checked_name(value, METHODS, "ground method")


def engine_name(value: object) -> str:
    """``value`` when it is a name of :data:`ENGINES`; :class:`InputError` otherwise."""
    return _checked_name(value, ENGINES, "engine")


def default_params(method: str) -> Params:
    """The PDAL defaults of a method (``"csf"`` or ``"smrf"``)."""
    return CsfParams() if method_name(method) == "csf" else SmrfParams()


def method_params(method: str, params: Optional[Params] = None) -> Params:
    """``params`` (the method's defaults when ``None``), checked to belong to ``method``
    (a name of :data:`METHODS`)."""
    if params is None:
        return default_params(method)
    if not isinstance(params, CsfParams if method == "csf" else SmrfParams):
        raise InputError("Parameters {params} do not belong to method {method}",
                         params=type(params).__name__, method=method)
    return params


def grid_step_m(params: Params) -> float:
    """The grid step of the method: CSF's cloth resolution or SMRF's cell (metres)."""
    return params.resolution if isinstance(params, CsfParams) else params.cell
