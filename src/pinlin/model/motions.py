"""Periodic prescribed joint motions q_p(t) (theory: Floquet): :class:`Harmonic`, :class:`FourierMotion`,
:class:`PeriodicMotion`, and the common period of several (:func:`common_period`).

A prescribed joint turns at a constant velocity (a number in ``Scene(prescribed=...)``) or follows one
of these: q_p(t) [rad or m], v_p(t) and a_p(t) are given functions of time, not coordinates.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np

from ..errors import ParameterError, PrescribedJointError, QuasiPeriodicError
from .numbers import numeric_scalar

__all__ = [
    "Motion",
    "Harmonic",
    "FourierMotion",
    "PeriodicMotion",
    "common_period",
    "split_prescribed",
    "harmonic_from_table",
    "HARMONIC_KEYS",
    "DERIVATIVE_RTOL",
    "DERIVATIVE_CHECK_TIMES",
    "MAX_PERIOD_DENOMINATOR",
    "PERIOD_RATIO_RTOL",
]

#: Relative tolerance of the difference check of a :class:`PeriodicMotion`'s derivatives: at h = 1e-4 T
#: truncation (7e-8 of a harmonic's) and rounding (eps |q| / h) stay 100 times below; a wrong sign fails.
DERIVATIVE_RTOL = 1e-5
#: Fractions of the period where a :class:`PeriodicMotion`'s derivatives are checked (irregular: no symmetry hides an error).
DERIVATIVE_CHECK_TIMES = (0.0, 0.1234, 0.3771, 0.5, 0.7219, 0.9006)
#: Largest denominator of a period ratio accepted as rational by :func:`common_period`.
MAX_PERIOD_DENOMINATOR = 12
#: Relative tolerance within which a period ratio must equal its rational approximation p / r.
PERIOD_RATIO_RTOL = 1e-12


def _real(value, name: str, *, positive: bool = False) -> float:
    x = numeric_scalar(value, name)  # text and booleans are refused, as for every element's numbers
    if not math.isfinite(x):
        raise ParameterError(name, f"must be finite, got {value!r}")
    if positive and not x > 0:
        raise ParameterError(name, f"must be positive, got {value!r}")
    return x


class Motion:
    """Base class of a prescribed periodic motion: ``q(t)``, ``v(t)``, ``a(t)`` of t [s] and ``period`` T > 0 [s].

    Examples
    --------
    >>> motion = pinlin.Harmonic(amplitude=0.1, omega=2.0)
    >>> isinstance(motion, pinlin.model.Motion), motion.omega
    (True, 2.0)
    """

    period: float

    def __setattr__(self, name, value):
        # immutable once made (a scene holding it is shared by threads): subclasses set _frozen last
        if self.__dict__.get("_frozen", False):
            raise AttributeError(f"{type(self).__name__} is immutable: cannot set {name!r}; make a new one")
        object.__setattr__(self, name, value)

    def q(self, t: float) -> float:  # pragma: no cover (abstract)
        raise NotImplementedError

    def v(self, t: float) -> float:  # pragma: no cover (abstract)
        raise NotImplementedError

    def a(self, t: float) -> float:  # pragma: no cover (abstract)
        raise NotImplementedError

    @property
    def omega(self) -> float:
        """Fundamental angular frequency 2 pi / T [rad/s]."""
        return 2.0 * math.pi / self.period


class FourierMotion(Motion):
    """A Fourier series q(t) = offset + sum_k (c_k cos(k omega t) + s_k sin(k omega t)), k = 1..K.

    Parameters
    ----------
    cosines, sines : sequences of float
        c_1..c_K and s_1..s_K [rad or m]; the shorter one is padded with zeros.
    omega : float
        Fundamental angular frequency [rad/s], nonzero (its sign is folded into the sines).
    offset : float
        Mean position [rad or m].

    Notes
    -----
    .. math::
        v(t) = \\sum_k k\\omega (s_k \\cos k\\omega t - c_k \\sin k\\omega t), \\qquad
        a(t) = -\\sum_k (k\\omega)^2 (c_k \\cos k\\omega t + s_k \\sin k\\omega t)

    Raises
    ------
    ParameterError
        Non-finite coefficients, omega zero or non-finite, no coefficient.

    Examples
    --------
    >>> motion = pinlin.FourierMotion(cosines=[0.1], sines=[0.0, 0.05], omega=3.0)
    >>> print(f"{motion.period:.6f} {motion.q(0.0):.6f}")
    2.094395 0.100000
    """

    def __init__(self, cosines: Iterable[float] = (), sines: Iterable[float] = (), omega: float = 1.0,
                 offset: float = 0.0):
        c = [_real(x, f"cosines[{i}]") for i, x in enumerate(cosines)]
        s = [_real(x, f"sines[{i}]") for i, x in enumerate(sines)]
        w = _real(omega, "omega")
        if w == 0:
            raise ParameterError("omega", "must be nonzero (a constant position is not a periodic motion)")
        if w < 0:  # cos is even, sin odd: q(t) with -omega is q(t) with omega and the sines negated
            w, s = -w, [-x for x in s]
        K = max(len(c), len(s))
        if K == 0:
            raise ParameterError("cosines", "a Fourier motion needs at least one coefficient")
        self.cosines, self.sines = np.array(c + [0.0] * (K - len(c))), np.array(s + [0.0] * (K - len(s)))
        self.cosines.flags.writeable = self.sines.flags.writeable = False
        self.fundamental = w
        self.offset = _real(offset, "offset")
        self.period = 2.0 * math.pi / w
        self._k = np.arange(1, K + 1) * w
        self._k.flags.writeable = False
        self._frozen = True

    def _cs(self, t: float):
        x = self._k * float(t)
        return np.cos(x), np.sin(x)

    def q(self, t: float) -> float:
        cos, sin = self._cs(t)
        return self.offset + float(self.cosines @ cos + self.sines @ sin)

    def v(self, t: float) -> float:
        cos, sin = self._cs(t)
        return float((self._k * self.sines) @ cos - (self._k * self.cosines) @ sin)

    def a(self, t: float) -> float:
        cos, sin = self._cs(t)
        k2 = self._k**2
        return -float((k2 * self.cosines) @ cos + (k2 * self.sines) @ sin)

    def __repr__(self) -> str:
        return (f"FourierMotion(cosines={self.cosines.tolist()}, sines={self.sines.tolist()}, "
                f"omega={self.fundamental!r}, offset={self.offset!r})")


class Harmonic(Motion):
    """q(t) = offset + amplitude sin(omega t + phase) [rad or m] (theory: Floquet).

    .. math::
        v(t) = A\\omega \\cos(\\omega t + \\varphi), \\qquad a(t) = -A\\omega^2 \\sin(\\omega t + \\varphi)

    Parameters
    ----------
    amplitude : float
        A [rad or m], finite (zero allowed: the joint is held at ``offset``).
    omega : float
        Angular frequency [rad/s], nonzero; T = 2 pi / |omega|.
    offset, phase : float
        Mean position [rad or m] and phase [rad]; ``phase = pi / 2`` gives offset + A cos(omega t).

    Raises
    ------
    ParameterError
        A non-finite parameter or omega = 0 (naming it).

    Examples
    --------
    >>> motion = pinlin.Harmonic(amplitude=0.1, omega=2.0)
    >>> print(f"{motion.period:.6f} {motion.q(0.25):.6f} {motion.v(0.0):.6f}")
    3.141593 0.047943 0.200000
    """

    def __init__(self, amplitude: float, omega: float, offset: float = 0.0, phase: float = 0.0):
        self.amplitude = _real(amplitude, "amplitude")
        self.frequency = _real(omega, "omega")
        if self.frequency == 0:
            raise ParameterError("omega", "must be nonzero (a constant position is not a periodic motion)")
        self.offset = _real(offset, "offset")
        self.phase = _real(phase, "phase")
        self.period = 2.0 * math.pi / abs(self.frequency)
        self._frozen = True

    def q(self, t: float) -> float:
        return self.offset + self.amplitude * math.sin(self.frequency * t + self.phase)

    def v(self, t: float) -> float:
        return self.amplitude * self.frequency * math.cos(self.frequency * t + self.phase)

    def a(self, t: float) -> float:
        return -self.amplitude * self.frequency**2 * math.sin(self.frequency * t + self.phase)

    def __repr__(self) -> str:
        return (f"Harmonic(amplitude={self.amplitude!r}, omega={self.frequency!r}, offset={self.offset!r}, "
                f"phase={self.phase!r})")


class PeriodicMotion(Motion):
    """A general T-periodic motion given by three callables q(t), v(t), a(t) and its period.

    v and a are checked against central differences (step 1e-4 T) of q and v at the fractions
    :data:`DERIVATIVE_CHECK_TIMES` of T, relative to max |v| and max |a|, and q, v, a must repeat after T.

    Parameters
    ----------
    q, v, a : callable float -> float
        Position [rad or m], velocity and acceleration at time t [s].
    period : float
        T [s], positive and finite.
    rtol : float
        The derivatives' relative tolerance of the check by differences (default :data:`DERIVATIVE_RTOL`).

    Raises
    ------
    ParameterError
        A bad period, a callable that fails or returns a non-finite number, derivatives that
        disagree with the differences, or a motion that does not repeat after T.

    Examples
    --------
    >>> motion = pinlin.PeriodicMotion(np.sin, np.cos, lambda t: -np.sin(t), 2 * np.pi)
    >>> print(f"{motion.q(np.pi / 2):.6f} {motion.a(np.pi / 2):.6f}")
    1.000000 -1.000000
    """

    def __init__(self, q: Callable[[float], float], v: Callable[[float], float], a: Callable[[float], float],
                 period: float, *, rtol: float = DERIVATIVE_RTOL):
        self.period = _real(period, "period", positive=True)
        for name, f in (("q", q), ("v", v), ("a", a)):
            if not callable(f):
                raise ParameterError(name, f"expected a callable t -> float, got {f!r}")
        self._q, self._v, self._a = q, v, a
        self._check(rtol)
        self._frozen = True

    def _value(self, name: str, f, t: float) -> float:
        try:
            x = float(f(t))
        except Exception as exc:  # a user's callable: report what failed, whatever it raised
            raise ParameterError(name, f"the motion's {name}(t) failed at t = {t!r}: {exc!r}") from None
        if not math.isfinite(x):
            raise ParameterError(name, f"the motion's {name}(t) = {x!r} at t = {t!r} is not finite")
        return x

    def _check(self, rtol: float) -> None:
        T = self.period
        h = 1e-4 * T
        times = [s * T for s in DERIVATIVE_CHECK_TIMES]
        grid = [i * T / 64 for i in range(64)]
        scale = {n: max(abs(self._value(n, f, t)) for t in grid) for n, f in (("q", self._q), ("v", self._v), ("a", self._a))}
        for name, f, df, dname in (("q", self._q, self._v, "v"), ("v", self._v, self._a, "a")):
            for t in times:
                fd = (self._value(name, f, t + h) - self._value(name, f, t - h)) / (2 * h)
                d = self._value(dname, df, t)
                if not abs(d - fd) <= rtol * max(scale[dname], abs(fd)) + 1e-300:
                    raise ParameterError(
                        dname,
                        f"the motion's {dname}({t:.6g}) = {d:.10g} disagrees with the central difference of "
                        f"{name}, {fd:.10g} (relative {abs(d - fd) / max(scale[dname], abs(fd), 1e-300):.2e} > "
                        f"{rtol:g}): {dname} must be the time derivative of {name}",
                    )
        for name, f in (("q", self._q), ("v", self._v), ("a", self._a)):
            for t in times:
                gap = abs(self._value(name, f, t + T) - self._value(name, f, t))
                if not gap <= rtol * (scale[name] + (1.0 if name == "q" else 0.0)):
                    raise ParameterError(
                        "period", f"the motion's {name} does not repeat after T = {T:g} s: "
                                  f"{name}(t + T) - {name}(t) = {gap:.3g} at t = {t:.6g}")

    def q(self, t: float) -> float:
        return float(self._q(t))

    def v(self, t: float) -> float:
        return float(self._v(t))

    def a(self, t: float) -> float:
        return float(self._a(t))

    def __repr__(self) -> str:
        return f"PeriodicMotion(period={self.period!r})"


def split_prescribed(robot, prescribed) -> tuple[dict[str, float], dict[str, Motion]]:
    """A scene's ``prescribed`` mapping checked and split: (constant velocities, periodic motions).

    Raises
    ------
    JointNotFoundError
        A name the robot lacks.
    PrescribedJointError
        A joint that is not 1-DOF.
    ParameterError
        A velocity that is not a finite number (nor a :class:`Motion`).
    """
    pres: dict[str, float] = {}
    motions: dict[str, Motion] = {}
    for name, omega in dict(prescribed or {}).items():
        j = robot.joint(name)
        if j.nv != 1:
            raise PrescribedJointError(
                f"prescribed joint {name!r} is a {j.kind} with {j.nv} degrees of freedom; "
                f"only 1-DOF joints (revolute, continuous, prismatic) can have a prescribed velocity or motion"
            )
        if isinstance(omega, Motion):
            motions[name] = omega
            continue
        try:
            omega = float(omega)
        except (TypeError, ValueError):
            raise ParameterError(f"prescribed[{name!r}]", "expected a number or a Harmonic / FourierMotion / "
                                 f"PeriodicMotion, got {omega!r}") from None
        if not math.isfinite(omega):
            raise ParameterError(f"prescribed[{name!r}]", f"must be finite, got {omega!r}")
        pres[name] = omega
    return pres, motions


#: The keys of a harmonic motion's table in a scene file's ``[prescribed]`` (amplitude and omega required).
HARMONIC_KEYS = ("amplitude", "omega", "offset", "phase")


def harmonic_from_table(table: dict) -> Harmonic:
    """A :class:`Harmonic` from a scene file's table ``{ amplitude = 0.02, omega = 60.0 }`` (``offset``, ``phase`` optional).

    Raises
    ------
    ParameterError
        An unknown or missing key, or a value :class:`Harmonic` refuses (naming the key).
    """
    unknown = sorted(set(table) - set(HARMONIC_KEYS))
    if unknown:
        raise ParameterError(unknown[0], f"unknown key of a harmonic motion; valid: {list(HARMONIC_KEYS)}")
    for key in ("amplitude", "omega"):
        if key not in table:
            raise ParameterError(key, "missing: a harmonic motion needs amplitude [rad or m] and omega [rad/s]")
    for key, value in table.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ParameterError(key, f"expected a number, got {value!r}")
    return Harmonic(**table)


def _ratio(x: float) -> tuple[int, int] | None:
    """(p, r) with x = p / r within :data:`PERIOD_RATIO_RTOL` and r <= :data:`MAX_PERIOD_DENOMINATOR`."""
    for r in range(1, MAX_PERIOD_DENOMINATOR + 1):
        p = round(x * r)
        if p > 0 and abs(p / r - x) <= PERIOD_RATIO_RTOL * x:
            return p, r
    return None


def common_period(periods: dict[str, float]) -> float | None:
    """The least common multiple of several periods [s] (joint name -> T_j), or None for none.

    Each ratio T_j / T_1 must be a fraction p / r (r <= :data:`MAX_PERIOD_DENOMINATOR`, within
    :data:`PERIOD_RATIO_RTOL`); T is the smallest period of which every T_j is a whole fraction.

    Raises
    ------
    QuasiPeriodicError
        Two periods whose ratio is not such a fraction (quasi-periodic: Floquet analysis does not apply).

    Examples
    --------
    >>> pinlin.model.common_period({"rotor": 1.0, "pitch": 1.5})
    3.0
    """
    if not periods:
        return None
    names = list(periods)
    first = names[0]
    T1 = periods[first]
    fractions = []
    for name in names:
        pr = _ratio(periods[name] / T1)
        if pr is None:
            raise QuasiPeriodicError(
                f"the periods of the prescribed motions of {first!r} (T = {T1:.12g} s) and {name!r} "
                f"(T = {periods[name]:.12g} s) have the ratio {periods[name] / T1:.15g}, not a fraction with a "
                f"denominator up to {MAX_PERIOD_DENOMINATOR} (within {PERIOD_RATIO_RTOL:g}): the motion is "
                f"quasi-periodic, and Floquet analysis (one common period) does not apply",
                periods,
            )
        fractions.append(pr)
    D = math.lcm(*(r for _, r in fractions))
    nums = [p * (D // r) for p, r in fractions]
    L = math.lcm(*nums)
    return T1 * L / D
