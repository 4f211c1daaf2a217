"""Scene dictionaries shared by the scene tests."""
import copy

STEEL = {"type": "elastic", "E": "210 GPa", "nu": 0.3}

BASE = {
    "profile": {"type": "paraboloid", "R": "10 mm"},
    "materials": {"body1": dict(STEEL), "body2": dict(STEEL)},
    "load_path": [{"ramp": {"force": "100 N", "steps": 10}}],
}


def base(**sections):
    """A valid normal-only scene (steel ball, 100 N); keyword sections replace or add tables."""
    d = copy.deepcopy(BASE)
    d.update(copy.deepcopy(sections))
    return d


def twist_scene(*segments, friction=0.2, **sections):
    """Preload 100 N then the given segments (default: a 2-cycle twist oscillation)."""
    segs = list(segments) or [{"sinusoid": {"twist": "2 mrad", "cycles": 2, "steps_per_cycle": 20}}]
    d = base(**sections)
    d["load_path"] = [{"ramp": {"force": "100 N", "steps": 10}}] + segs
    if friction is not None:
        d["interface"] = {"friction": friction}
    return d


def example_params():
    """Every example scene as a pytest param."""
    from pathlib import Path

    import pytest
    out = []
    for p in sorted((Path(__file__).parents[3] / "examples").glob("*.toml")):
        out.append(pytest.param(p, id=p.stem))
    return out
