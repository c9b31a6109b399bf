"""A fixed set of results whose values must not move when the code is reorganized.

:func:`compute` returns named arrays from the public API on the bundled scenes and a few robots; the stored
copy ``golden_values.npz`` was written by ``python tests/golden/golden_cases.py`` before the package's
layout changed, and ``test_golden.py`` compares the current values with it bitwise.  Regenerate it only
for a change that is meant to alter results, and say so in the commit.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import pinlin
import pinlin.model

HERE = Path(__file__).resolve().parent
STORE = HERE / "golden_values.npz"


def _system(out: dict, tag: str, sys) -> None:
    for name in ("M", "D", "G", "S", "N"):
        out[f"{tag}.{name}"] = np.asarray(getattr(sys, name))
    if getattr(sys, "basis", None) is not None:
        out[f"{tag}.basis"] = np.asarray(sys.basis)


def _modes(out: dict, tag: str, sys) -> None:
    modes = pinlin.modal_analysis(sys)
    out[f"{tag}.eigenvalues"] = np.asarray(modes.eigenvalues)
    out[f"{tag}.backward_error"] = np.asarray(modes.backward_error)
    out[f"{tag}.condition"] = np.asarray(modes.condition)
    out[f"{tag}.margin"] = np.array([modes.stability.margin])


def compute() -> dict[str, np.ndarray]:
    """The golden values, freshly computed."""
    out: dict[str, np.ndarray] = {}
    for name in ("double_pendulum", "double_pendulum_flutter", "four_bar", "turntable", "rotating_ring"):
        spec = pinlin.model.load_scene(pinlin.data_path(f"scenes/{name}.toml"))
        q = spec.q0
        if spec.equilibrium:
            eq = pinlin.find_equilibrium(spec.scene, q)
            q = eq.q
            out[f"{name}.eq.q"] = np.asarray(q)
        sys = pinlin.linearize(spec.scene, q, balancing=spec.balancing)
        _system(out, name, sys)
        _modes(out, name, sys)
        s = np.array([0.3 + 2.0j, 1.5j])
        out[f"{name}.flexibility"] = np.asarray(pinlin.flexibility(sys, s))
        t = np.linspace(0.0, 1.0, 5)
        x0 = np.linspace(0.01, 0.02, sys.n)
        out[f"{name}.free"] = np.asarray(pinlin.free_response(sys, x0, np.zeros(sys.n), t))
    ur5 = pinlin.load_example("ur5")
    scene = pinlin.Scene(ur5, [pinlin.JointSpring(j, 100.0) for j in ur5.joint_names], gravity=(0, 0, -9.81))
    q = np.zeros(ur5.model.nq)
    _system(out, "ur5", pinlin.linearize(scene, q + 0.1, balancing=True))
    qs = np.stack([q + 0.1 * k for k in range(3)])
    for k, sys in enumerate(pinlin.linearize_many(scene, qs, balancing=True)):
        _system(out, f"ur5.many{k}", sys)
    box = pinlin.load_urdf(pinlin.data_path("urdf/double_pendulum.urdf"))
    bush = pinlin.Bushing("tip", "base", stiffness=[1e3] * 3 + [10.0] * 3, damping=[1.0] * 6)
    spring = pinlin.LinearSpringDamper("tip", (0.3, 0.0, 1.0), stiffness=50.0, damping=0.5, rest_length=0.3)
    scene = pinlin.Scene(box, [bush, spring], gravity=(0, 0, -9.81))
    sys = pinlin.linearize(scene, np.array([0.3, -0.2]), balancing=True)
    _system(out, "frame_elements", sys)
    _modes(out, "frame_elements", sys)
    return out


if __name__ == "__main__":
    values = compute()
    np.savez(STORE, **values)
    print(f"wrote {len(values)} arrays to {STORE}")
