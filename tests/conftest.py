import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

# Hypothesis profiles: "ci", the default, runs the fuzz tests (tests/fuzz/) on a fixed set
# of examples (derandomized, 50 per test, about ten seconds together on 2 cores); "long"
# (`pytest tests/fuzz --hypothesis-profile=long`) explores thousands of fresh examples per test.
# Tests that set their own max_examples keep them; deadlines are per example in the fuzz tests
# themselves (a hang must be interrupted, which hypothesis's deadline cannot do).
from hypothesis import HealthCheck, settings  # noqa: E402

_SLOW = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]
settings.register_profile("ci", max_examples=50, deadline=None, derandomize=True, database=None,
                          suppress_health_check=_SLOW)
settings.register_profile("long", max_examples=3000, deadline=None, suppress_health_check=_SLOW)
settings.load_profile("ci")
