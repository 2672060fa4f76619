"""heavytop._core: the compiled bindings of the heavytop package (pybind11, NumPy).

Use the package instead (`import heavytop`): its functions give these their defaults and
wrap what they return in typed results (heavytop.results).
"""
from typing import Any, Dict, Literal, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
#: The SPEC names of every model, in SPEC order.
MODELS: Tuple[str, ...]
#: False when built without HEAVYTOP_BUILD_SYMBOLIC (GiNaC): derive*() raise RuntimeError.
HAS_DERIVE: bool

class InvalidInput(ValueError):
    """Bad input: "<key>: <rule>", the key a keyword argument's name or "body.*", "motion.*"."""

    key: str
    rule: str

class Body:
    """A rigid body turning about a fixed point O in uniform gravity (SPEC section 1). Immutable."""

    def __init__(self, A: float, B: float, C: float, mass: float, length: float, gravity: float = 9.81, *,
                 transverse_damping: float = 0.0, axial_damping: float = 0.0, friction: float = 0.0,
                 driven: bool = False, offset_x: float = 0.0, offset_y: float = 0.0, Ixy: float = 0.0,
                 Ixz: float = 0.0, Iyz: float = 0.0) -> None: ...
    @property
    def A(self) -> float: ...
    @property
    def B(self) -> float: ...
    @property
    def C(self) -> float: ...
    @property
    def mass(self) -> float: ...
    @property
    def length(self) -> float: ...
    @property
    def gravity(self) -> float: ...
    @property
    def mgR(self) -> float: ...
    @property
    def transverse_damping(self) -> float: ...
    @property
    def axial_damping(self) -> float: ...
    @property
    def friction(self) -> float: ...
    @property
    def driven(self) -> bool: ...
    @property
    def offset_x(self) -> float: ...
    @property
    def offset_y(self) -> float: ...
    @property
    def Ixy(self) -> float: ...
    @property
    def Ixz(self) -> float: ...
    @property
    def Iyz(self) -> float: ...
    @property
    def general(self) -> bool: ...
    def to_dict(self) -> Dict[str, float]: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def __getstate__(self) -> Tuple[Any, ...]: ...
    def __setstate__(self, state: Tuple[Any, ...]) -> None: ...


def example_toy_top() -> Body: ...
def example_motion() -> Dict[str, float]: ...
def grid_values(start: float, stop: float, count: int) -> npt.NDArray[np.float64]: ...
def read_map(path: str) -> Tuple[Dict[str, Any], Tuple[int, ...]]: ...

def stability(body: Body, spin: float, *, theta0: float = 0.0, phi0: float = 0.0, theta_rate0: float = 0.0,
              phi_rate0: float = 0.0, horizon: float = 100.0, max_tilt: float = 1.0) -> Tuple[Dict[str, Any], str]: ...
def lifetime(body: Body, *, spin: float, theta0: float, phi0: float, theta_rate0: float, phi_rate0: float,
             horizon: Optional[float] = None, max_tilt: float = 1.0, rtol: Optional[float] = None,
             atol: Optional[float] = None, max_steps: Optional[int] = None) -> Dict[str, Any]: ...
def simulate(
    body: Body,
    model: str,
    *,
    spin: float,
    theta0: float,
    phi0: float,
    theta_rate0: float,
    phi_rate0: float,
    t_end: float,
    samples: int,
    method: Optional[Literal["analytic", "numeric"]] = None,
    integrator: Optional[Literal["auto", "taylor", "dop853", "dopri5", "adaptive", "splitting"]] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    step: Optional[float] = None,
    order: Optional[int] = None,
    max_steps: Optional[int] = None,
) -> Tuple[Dict[str, npt.NDArray[np.float64]], Dict[str, Any]]: ...
def compare(
    body: Body,
    *,
    spin: float,
    theta0: float,
    phi0: float,
    theta_rate0: float,
    phi_rate0: float,
    t_end: float,
    samples: int,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
) -> Dict[str, Any]: ...
def sweep(
    body: Body,
    vary: Dict[str, npt.ArrayLike],
    *,
    spin: float,
    theta0: float,
    phi0: float,
    theta_rate0: float,
    phi_rate0: float,
    nonlinear: bool,
    horizon: float,
    max_tilt: float,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    integrator: Optional[str] = None,
) -> Dict[str, npt.NDArray[Any]]: ...
def derive(method: str, sequence: str, order: int) -> Dict[str, Any]: ...
def fit_decay(t: npt.ArrayLike, spin: npt.ArrayLike, body: Body, *, spin0: Optional[float] = None) -> Dict[str, Any]: ...
def derive_rotations(order: int) -> Dict[str, Any]: ...
def derive_check(order: Optional[int] = None) -> Dict[str, Any]: ...
def assemble_parts(text: str, source: str, gravity: float, allow_general: bool) -> Tuple[Dict[str, Any], Optional[Body]]: ...
def precession(body: Body, tilt: float, spin: float) -> Dict[str, Any]: ...
def rad_per_s_from_rpm(rpm: float) -> float: ...
def load_configuration(path: str) -> Tuple[Body, Dict[str, float], Dict[str, Any], list, bool]: ...
def write_report(folder: str, body: Body, spin: float, theta0: float, phi0: float, theta_rate0: float, phi_rate0: float,
                 t_end: Optional[float], map: str, held: str, values: list, source: str) -> None: ...
