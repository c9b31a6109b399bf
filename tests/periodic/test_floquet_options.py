"""The Floquet options validated once (FloquetOptions), and the deprecated keyword spellings of 0.4."""

from __future__ import annotations

import numpy as np
import pytest
from floquet_cases import mathieu
from numpy.testing import assert_allclose
from scene_cases import pivot_scene

import pinlin
from pinlin.errors import ParameterError
from pinlin.periodic import floquet_analysis_matrices
from pinlin.periodic.options import FloquetOptions


TWO_PI = 2 * np.pi


@pytest.mark.parametrize("name, value, match", [
    ("rtol", 1e-1, r"rtol: expected in \[1e-16, 1e-2\), got 0.1"),
    ("stages", 2.0, "stages: expected an int in 2..12, got 2.0"),
    ("growth", 5.0, r"growth: expected in \[10, 1e8\], got 5.0"),
    ("harmonics", -1, "harmonics: expected an int >= 0, got -1"),
    ("safety", np.nan, r"safety: expected in \[1, 1e6\), got nan"),
    ("max_steps", 0, "max_steps: expected an int >= 1, got 0"),
    ("max_time", -1.0, r"max_time: expected a time >= 0 \[s\], got -1.0"),
    ("sampling", "fft", "sampling: expected one of 'auto', 'spectral', 'nodes', got 'fft'"),
    ("max_samples", True, "max_samples: expected an int in 16..65536, got True"),
    ("structure_tol", -1.0, r"structure_tol: expected a number >= 0 \(units of eps\), got -1.0"),
])
def test_each_option_is_checked_by_name(name, value, match):
    with pytest.raises(ParameterError, match=match):
        FloquetOptions(**{name: value})
    with pytest.raises(ParameterError, match=match):
        floquet_analysis_matrices(*mathieu(1.3, 0.4), TWO_PI, **{name: value})


def test_numpy_scalars_become_python_numbers():
    options = FloquetOptions(stages=np.int64(4), rtol=np.float32(1e-10))
    assert type(options.stages) is int and options.stages == 4
    assert type(options.rtol) is float and options.rtol == pytest.approx(1e-10, rel=1e-7)


def test_the_defaults_are_the_module_constants():
    from pinlin.periodic import options as o
    assert FloquetOptions() == FloquetOptions(rtol=o.RTOL, stages=o.STAGES, growth=o.GROWTH, harmonics=o.HARMONICS,
                                              safety=o.SAFETY, max_steps=o.MAX_STEPS, max_time=o.MAX_TIME,
                                              sampling=o.SAMPLING, max_samples=o.MAX_SAMPLES,
                                              structure_tol=o.STRUCTURE_TOL)
    assert (o.RTOL, o.STAGES, o.SAMPLING, o.STRUCTURE_TOL) == (1e-13, 6, "auto", 100.0)


def test_structure_tolerance_is_the_deprecated_spelling_of_structure_tol():
    # the damped Mathieu equation: C = 0.1 is symmetric, not skew, so the structure defect is far above either
    new = floquet_analysis_matrices(*mathieu(1.3, 0.4, 0.1), TWO_PI, structure_tol=1e3)
    with pytest.warns(DeprecationWarning, match=r"floquet_analysis_matrices\(structure_tolerance=...\) is "
                                                r"deprecated since pinlin 0.4 .* use structure_tol=..."):
        old = floquet_analysis_matrices(*mathieu(1.3, 0.4, 0.1), TWO_PI, structure_tolerance=1e3)
    assert not old.conservative and not new.conservative
    assert_allclose(old.multipliers, new.multipliers, rtol=0, atol=0)
    # Liouville: det Phi(T) = exp(-0.1 T)
    assert_allclose(np.prod(old.multipliers).real, np.exp(-0.1 * TWO_PI), rtol=1e-12)
    with pytest.raises(ParameterError, match="structure_tolerance: is the deprecated name of structure_tol"):
        floquet_analysis_matrices(*mathieu(1.3, 0.4), TWO_PI, structure_tolerance=1.0, structure_tol=1.0)


def _kapitza():
    spec = pinlin.model.load_scene(pinlin.data_path("scenes/kapitza.toml"))
    return spec, pinlin.periodic_orbit(spec.scene, spec.q0)


def test_floquet_analysis_spells_out_its_options():
    spec, orbit = _kapitza()
    with pytest.raises(ParameterError, match="stages: expected an int in 2..12, got 20"):
        pinlin.floquet_analysis(spec.scene, orbit, stages=20)
    with pytest.raises(TypeError, match="unexpected keyword argument 'tolerance'"):
        pinlin.floquet_analysis(spec.scene, orbit, tolerance=1e-9)
    with pytest.warns(DeprecationWarning, match=r"floquet_analysis\(structure_tolerance=...\)"):
        old = pinlin.floquet_analysis(spec.scene, orbit, structure_tolerance=100.0)
    new = pinlin.floquet_analysis(spec.scene, orbit, rtol=1e-10)
    assert "rtol = 1e-10" in new.method      # the rtol given reaches the integration
    assert_allclose(np.abs(old.multipliers), 1.0, rtol=1e-10)   # undamped: on the unit circle


def test_tol_is_the_deprecated_spelling_of_residual_tol():
    scene = pivot_scene({"pivot_x": pinlin.Harmonic(1e-3, 3.0)}, elements=[pinlin.JointDamper("swing", 0.2)])
    q0 = np.zeros(scene.model.nq)
    new = pinlin.periodic_orbit(scene, q0, residual_tol=1e-9)
    with pytest.warns(DeprecationWarning, match=r"periodic_orbit\(tol=...\) is deprecated .* use residual_tol=..."):
        old = pinlin.periodic_orbit(scene, q0, tol=1e-9)
    assert old.residual <= 1e-9 and new.residual <= 1e-9 and old.iterations == new.iterations
    assert_allclose(old.q0, new.q0, rtol=0, atol=0)
    with pytest.raises(ParameterError, match="tol: is the deprecated name of residual_tol"):
        pinlin.periodic_orbit(scene, q0, tol=1e-9, residual_tol=1e-9)
