"""Every result lists the sources its computation used; cite() prints them; tags resolve.

The expected tags per effect are written here from the literature each computation follows (not
read back from contactlab.citations.EFFECT_SOURCES): Sneddon's solution and the MDR handbook for
normal contact, Heß's rule and JKR for adhesion, Cattaneo and Mindlin for tangential contact,
Reissner–Sagoci / Jäger / the seed paper for the three torsion models, Lee–Radok, Ting and the
viscoelastic handbook for viscoelastic media, Vingsbo–Söderberg and Fouvry for fretting.
"""
from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest

import contactlab as cl
from contactlab.citations import SOURCES, Citations, bibliography_markdown
from contactlab.errors import ParameterError, UnknownNameError

ROOT = Path(__file__).resolve().parents[2]
STEEL = cl.Elastic(E=210e9, nu=0.3)
MDR = {"PH", "H1"}


def _contact(**kw):
    return cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(STEEL, STEEL), **kw)


def _tags(result) -> set[str]:
    return set(result.citations.tags)


def test_normal():
    assert _tags(_contact().normal(force=10.0)) == MDR | {"Sn65"}


def test_adhesion():
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=1.5e6, nu=0.5),
                   cl.Rigid()), work_of_adhesion=0.05)
    assert {"Heß11", "JKR71"} | MDR <= _tags(c.normal(depth=1e-6))
    assert {"Heß11", "JKR71"} <= _tags(c.pull_off())
    assert {"Heß11", "JKR71"} <= _tags(c.adhesion_cycle(depth=np.linspace(-1e-6, 1e-6, 5)))
    punch = cl.Contact(cl.profiles.FlatPunch(radius=1e-3), materials=(cl.Elastic(E=1.5e6, nu=0.5),
                       cl.Rigid()), work_of_adhesion=0.05)
    assert "K71" in _tags(punch.normal(depth=1e-6))
    assert "K71" not in _tags(c.normal(depth=1e-6))


def test_tangential():
    c = _contact(friction=0.3)
    assert {"Cat38", "Min49"} | MDR <= _tags(c.tangential(force=10.0, displacement=1e-7))
    h = c.shift_history(force=10.0, displacement=1e-7 * np.sin(np.linspace(0, 6, 30)))
    assert {"Cat38", "Min49", "MD53"} <= _tags(h)


@pytest.mark.parametrize("method, expected, absent", [
    ("no-slip", {"RS44"}, {"J95", "S"}),
    ("exact", {"J95", "RS44"}, {"S"}),
    ("mdr", {"S"}, {"J95"}),
])
def test_torsion(method, expected, absent):
    c = _contact(friction=0.3)
    t = _tags(c.torsion(force=10.0, twist=1e-5, method=method))
    assert expected | MDR <= t and not (absent & t)
    h = c.twist_history(force=10.0, twist=1e-5 * np.sin(np.linspace(0, 6, 30)), method=method)
    assert expected | {"D54"} <= _tags(h)


def test_viscoelastic():
    from contactlab.materials.viscoelastic import KelvinVoigt
    kv = KelvinVoigt(G=1e6, eta=1e3)
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(kv, cl.Rigid()))
    h = c.viscoelastic_history(time=np.linspace(0, 1, 11), depth=np.linspace(0, 1e-5, 11))
    assert {"H3", "LR60", "T66"} <= _tags(h)


def test_foundation_path():
    c = _contact(friction=0.3)
    res = c.simulate(cl.LoadPath().ramp(force=10.0, steps=5).sinusoid(twist=1e-5, cycles=1,
                                                                     steps_per_cycle=8),
                     n_springs=50, method="mdr")
    assert MDR | {"S"} <= _tags(res)
    exact = c.simulate(cl.LoadPath().ramp(force=10.0, steps=5).sinusoid(twist=1e-5, cycles=1,
                                                                       steps_per_cycle=8),
                       method="exact")
    assert MDR | {"J95"} <= _tags(exact) and "S" not in _tags(exact)


def test_fretting():
    c = _contact(friction=0.5)
    assert {"VS88", "F96", "Cat38", "MD53"} <= _tags(
        c.fretting_loop(force=100.0, displacement_amplitude=1e-6, n_points=20))
    assert {"VS88", "F96", "J95", "D54"} <= _tags(
        c.fretting_loop(force=100.0, twist_amplitude=1e-4, n_points=20))


def test_scene():
    from contactlab.scene import Scene
    res = Scene.from_toml(ROOT / "examples" / "steel_ball_twist.toml").run()
    assert {"J95"} | MDR <= _tags(res) or {"S"} | MDR <= _tags(res)


def _every_result():
    """One instance of every public result type, with the sources its computation follows
    (written from the literature, see the module docstring)."""
    from contactlab.materials.viscoelastic import KelvinVoigt
    from contactlab.scene import Scene
    c = _contact(friction=0.5)
    adh = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(E=1.5e6, nu=0.5),
                     cl.Rigid()), work_of_adhesion=0.05)
    visco = cl.Contact(cl.profiles.Paraboloid(R=0.01),
                       materials=(KelvinVoigt(G=1e6, eta=1e3), cl.Rigid()))
    law = cl.ContactLaw(cl.profiles.Paraboloid, R=[0.01, 0.02], E_star=1e11, G_star=8e10,
                        G_torsion=4e10, friction=0.3)
    law.step(depth=[1e-7, 1e-7])
    step = law.step(depth=[1e-7, 1e-7], twist=[1e-6, 1e-6])
    path = cl.LoadPath().ramp(force=10.0, steps=5).sinusoid(twist=1e-5, cycles=1,
                                                           steps_per_cycle=8)
    hertz, cm, jaeger = {"Sn65"} | MDR, {"Cat38", "Min49"}, {"J95"}
    fretting, masing_t = {"VS88", "F96"}, {"D54", "MD53"}
    return {
        "NormalState": (c.normal(force=10.0), hertz),
        "AdhesiveNormalState": (adh.normal(depth=1e-6), {"Heß11", "JKR71"}),
        "AdhesionCycle": (adh.adhesion_cycle(depth=np.linspace(-1e-6, 1e-6, 5)),
                          {"Heß11", "JKR71"}),
        "ViscoelasticHistory": (visco.viscoelastic_history(time=np.linspace(0, 1, 5),
                                                           depth=np.linspace(0, 1e-5, 5)),
                                {"H3", "LR60", "T66"}),
        "TangentialState": (c.tangential(force=10.0, displacement=1e-7), cm | hertz),
        "ShiftHistory": (c.shift_history(force=10.0, displacement=[0, 1e-7, -1e-7]),
                         cm | {"MD53"}),
        "TorsionState": (c.torsion(force=10.0, twist=1e-5), jaeger | hertz),
        "TwistHistory": (c.twist_history(force=10.0, twist=[0, 1e-5, -1e-5]),
                         jaeger | {"D54"}),
        "PathResult": (c.simulate(path, method="exact"), jaeger | MDR),
        "ContactLaw": (law, hertz | cm | jaeger | masing_t),
        "LawStep": (step, hertz | cm | jaeger | masing_t),
        "FrettingLoop": (c.fretting_loop(force=100.0, twist_amplitude=1e-4, n_points=4),
                         fretting | jaeger | {"D54"}),
        "FrettingMap": (c.fretting_map(force=[100.0], displacement_amplitude=[1e-7, 1e-5]),
                        fretting | cm | {"MD53"}),
        "WearResult": (c.wear(force=100.0, displacement_amplitude=1e-6, wear_coefficient=1e-15,
                              cycles=1e3, n_grid=40),
                       {"D14"} | fretting | cm | {"MD53"}),
        "SceneResult": (Scene.from_toml(ROOT / "examples" / "steel_ball_twist.toml").run(),
                        MDR),
    }


#: public dataclasses that are not results of a computation (nothing to cite): inputs, plans,
#: the cost tool's report on numeric knobs
NOT_RESULTS = {"LoadPath", "MapPlan", "Scene", "History", "Effect", "Plan", "CostReport", "Grid"}


@pytest.mark.filterwarnings(r"ignore:wear\(\). the grid of:contactlab.errors.ValidityWarning")
def test_every_result_type_cites_what_it_used():
    """cite(result) works for every public result type (issue 26: it raised ParameterError for a
    WearResult), and the sources are those of the computation."""
    import dataclasses
    import importlib
    import inspect
    results = _every_result()
    mods = ["contactlab", "contactlab.scene", "contactlab.sweeps"] + [
        f"contactlab.effects.{m}" for m in ("adhesion", "fretting", "law", "normal", "path",
                                            "tangential", "torsion", "viscoelastic", "wear")]
    public = set()
    for m in mods:
        mod = importlib.import_module(m)
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name, None)
            if inspect.isclass(obj) and (dataclasses.is_dataclass(obj) or hasattr(obj, "to_dict")
                                         or hasattr(obj, "step")):
                public.add(name)
    assert public - NOT_RESULTS <= set(results), public - NOT_RESULTS - set(results)
    for name, (obj, expected) in results.items():
        assert type(obj).__name__ == name
        out = cl.cite(obj, file=None)
        assert out.startswith("This computation relied on:"), name
        assert expected <= _tags(obj), (name, _tags(obj))
    # the law's springs are cited only for a step in which some contact left the closed forms
    law = results["ContactLaw"][0]
    assert np.all(results["LawStep"][0].exact) and "S" not in _tags(results["LawStep"][0])
    varied = law.step(depth=[2e-7, 1e-7], twist=[2e-6, 2e-6])      # contact 0: load changed
    assert not np.all(varied.exact) and "S" in _tags(varied)


def test_cite_prints_text_and_bibtex():
    s = _contact(friction=0.3).torsion(force=10.0, twist=1e-5)
    buf = io.StringIO()
    out = cl.cite(s, file=buf)
    assert buf.getvalue().rstrip("\n") == out
    assert "Jäger" in out and "@article{Jaeger1995," in out and "@book{Popov2015MDR," in out
    assert cl.cite(s, format="bibtex", file=None).startswith("@")
    assert "[JKR71]" in cl.cite("JKR71", format="text", file=None)
    assert "[PH]" in cl.cite(file=None)


def test_cite_bad_input():
    with pytest.raises(ParameterError, match="format"):
        cl.cite(format="html", file=None)
    with pytest.raises(UnknownNameError, match="XYZ99"):
        cl.cite("XYZ99", file=None)
    with pytest.raises(ParameterError, match="cite"):
        cl.cite(3.0, file=None)


def test_bibtex_entries_are_balanced():
    text = Citations(SOURCES).bibtex()
    assert text.count("{") == text.count("}")
    assert len(set(s.key for s in SOURCES.values())) == len(SOURCES)


def test_references_page_is_generated():
    page = (ROOT / "docs" / "about" / "references.md").read_text(encoding="utf-8")
    assert page == bibliography_markdown(), (
        "docs/about/references.md is out of date: regenerate it with "
        "python -c \"from contactlab.citations import bibliography_markdown as b; "
        "open('docs/about/references.md', 'w').write(b())\"")


from tests.repo_files import repository_files  # noqa: E402

# ------------------------------------------------------------------ every tag used resolves
_TAG = re.compile(r"^(S|PH|H\d|[A-Z][a-zß]*\d{2})$")
_BRACKET = re.compile(r"\[([^\[\]\n]{1,80})\]")
_FILES = [p for p in repository_files() if p.suffix in {".py", ".md", ".toml", ".txt", ".cfg"}]


def _used_tags() -> dict[str, str]:
    found: dict[str, str] = {}
    for path in _FILES:
        for m in _BRACKET.finditer(path.read_text(encoding="utf-8", errors="replace")):
            for part in re.split(r"[;,/]", m.group(1)):
                word = part.strip().split(" ")[0] if part.strip() else ""
                if _TAG.match(word):
                    found.setdefault(word, str(path.relative_to(ROOT)))
    return found


def test_every_source_tag_used_in_the_repository_resolves():
    used = _used_tags()
    assert {"J95", "H1", "S"} <= set(used)            # the scan sees the tags we know are used
    unknown = {t: f for t, f in used.items() if t not in SOURCES}
    assert not unknown, f"source tags without a bibliography entry (citations.SOURCES): {unknown}"
