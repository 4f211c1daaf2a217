"""The sources a computation relied on, and :func:`cite` to print them.

Every result object of contactlab records the papers its computation used in
``result.citations`` (a :class:`Citations` tuple of :class:`Source`), e.g. Jäger's flat-punch
superposition for exact torsion or the seed paper's narrow-slip rule for the MDR torsion model.
``contactlab.cite(result)`` prints them as text and BibTeX, like PyBaMM's citation report.

The source tags used in docstrings and in the documentation (``[J95]``, ``[H1]``, ``[Heß11]``,
...) are the keys of :data:`SOURCES`; the bibliography page of the documentation is generated from
this table (:func:`bibliography_markdown`), and a test checks that every tag used anywhere in the
repository resolves here.

Examples
--------
>>> import contactlab as cl
>>> steel = cl.Elastic(E=210e9, nu=0.3)
>>> c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(steel, steel), friction=0.3)
>>> s = c.torsion(force=100.0, twist=1e-4)
>>> s.citations.tags
('PH', 'H1', 'Sn65', 'J95', 'RS44')
>>> print(cl.cite(s, format="text", file=None).splitlines()[4])
[J95] J. Jäger, "Axi-symmetric bodies of equal material in contact under torsion or shift", Archive of Applied Mechanics 65 (1995) 478-487.
"""  # noqa: E501 - a doctest's expected output line
from __future__ import annotations

import sys
from collections.abc import Iterable
from dataclasses import dataclass
from typing import IO, Any

from .errors import ParameterError, UnknownNameError

__all__ = ["Source", "Citations", "Cited", "SOURCES", "EFFECT_SOURCES", "sources_for", "cite",
           "bibliography_markdown"]


@dataclass(frozen=True)
class Source:
    """One bibliographic source.

    Attributes
    ----------
    tag : str
        Short tag used in docstrings and docs, e.g. ``"J95"`` (written ``[J95]``).
    key : str
        BibTeX key (ASCII).
    kind : str
        BibTeX entry type: ``"article"``, ``"book"``, ``"phdthesis"``.
    authors : str
        Authors as printed.
    title : str
    venue : str
        Journal, publisher or school.
    year : int
    volume, pages, doi : str
        Empty when not applicable or not known.
    used_for : str
        What contactlab uses the source for (one line).
    """

    tag: str
    key: str
    kind: str
    authors: str
    title: str
    venue: str
    year: int
    volume: str = ""
    pages: str = ""
    doi: str = ""
    used_for: str = ""

    def text(self) -> str:
        """One-line human-readable reference."""
        vol = f" {self.volume}" if self.volume else ""
        pages = f" {self.pages}" if self.pages else ""
        doi = f" doi:{self.doi}" if self.doi else ""
        return (f"[{self.tag}] {self.authors}, \"{self.title}\", {self.venue}{vol} "
                f"({self.year}){pages}.{doi}")

    def bibtex(self) -> str:
        """The BibTeX entry."""
        venue_field = {"article": "journal", "book": "publisher",
                       "phdthesis": "school"}.get(self.kind, "howpublished")
        authors = " and ".join(a.strip() for a in self.authors.replace(" & ", ", ").split(", "))
        fields = [("author", authors), ("title", "{" + self.title + "}"),
                  (venue_field, self.venue), ("year", str(self.year)),
                  ("volume", self.volume), ("pages", self.pages.replace("-", "--")),
                  ("doi", self.doi), ("note", f"contactlab: {self.used_for}" if self.used_for else "")]
        body = ",\n".join(f"  {k} = {{{v}}}" for k, v in fields if v)
        return f"@{self.kind}{{{self.key},\n{body}\n}}"


def _s(tag, key, kind, authors, title, venue, year, volume="", pages="", doi="", used_for=""):
    return tag, Source(tag, key, kind, authors, title, venue, year, volume, pages, doi, used_for)


#: Every source contactlab cites, by tag.
SOURCES: dict[str, Source] = dict([
    _s("PH", "Popov2015MDR", "book", "V. L. Popov, M. Heß",
       "Method of Dimensionality Reduction in Contact Mechanics and Friction",
       "Springer, Berlin Heidelberg", 2015, doi="10.1007/978-3-642-53876-6",
       used_for="the MDR: transform, foundation, normal, tangential and adhesive rules"),
    _s("H1", "Popov2014Handbook1", "article", "V. L. Popov, M. Heß",
       "Method of dimensionality reduction in contact mechanics and friction: a user's "
       "handbook. I. Axially-symmetric contacts",
       "Facta Universitatis, Series: Mechanical Engineering", 2014, "12(1)", "1-14",
       used_for="MDR rules for normal, adhesive and tangential contact; effective moduli"),
    _s("H3", "Popov2018Handbook3", "article", "V. L. Popov, E. Willert, M. Heß",
       "Method of dimensionality reduction in contact mechanics and friction: a user's "
       "handbook. III. Viscoelastic contacts",
       "Facta Universitatis, Series: Mechanical Engineering", 2018, "16(2)", "99-113",
       "10.22190/FUME180327013P",
       used_for="MDR rules for viscoelastic media (rheological elements scaled by 4 dx)"),
    _s("S", "MDRTorsionSeed", "article", "V. L. Popov, M. Heß and co-workers (TU Berlin)",
       "Application of the method of dimensionality reduction to contacts under normal and "
       "torsional loading", "Facta Universitatis, Series: Mechanical Engineering", 2015,
       used_for="the seed paper: torsional MDR springs 8 G_t dx and the narrow-slip model "
                "(mu* = 2 mu, eqs. 47-52); equation numbers in contactlab refer to it"),
    _s("Sn65", "Sneddon1965", "article", "I. N. Sneddon",
       "The relation between load and penetration in the axisymmetric Boussinesq problem for a "
       "punch of arbitrary profile", "International Journal of Engineering Science", 1965,
       "3", "47-57", "10.1016/0020-7225(65)90019-4",
       used_for="the exact axisymmetric frictionless normal contact the MDR reproduces"),
    _s("J85", "Johnson1985", "book", "K. L. Johnson", "Contact Mechanics",
       "Cambridge University Press, Cambridge", 1985, doi="10.1017/CBO9781139171731",
       used_for="Hertz contact, effective modulus, Mindlin's tangential contact, reference values"),
    _s("JKR71", "Johnson1971", "article", "K. L. Johnson, K. Kendall, A. D. Roberts",
       "Surface energy and the contact of elastic solids",
       "Proceedings of the Royal Society of London A", 1971, "324", "301-313",
       "10.1098/rspa.1971.0141", used_for="JKR adhesion of spheres; pull-off forces"),
    _s("Heß11", "Hess2011", "phdthesis", "M. Heß",
       "Über die exakte Abbildung ausgewählter dreidimensionaler Kontakte auf Systeme mit "
       "niedrigerer räumlicher Dimension", "Technische Universität Berlin (Cuvillier, Göttingen)",
       2011, used_for="the MDR adhesion rule: critical spring elongation sqrt(2 pi a dgamma / E*)"),
    _s("DMT75", "Derjaguin1975", "article", "B. V. Derjaguin, V. M. Muller, Yu. P. Toporov",
       "Effect of contact deformations on the adhesion of particles",
       "Journal of Colloid and Interface Science", 1975, "53", "314-326",
       "10.1016/0021-9797(75)90018-1", used_for="DMT adhesion: Hertz force less 2 pi R dgamma"),
    _s("M92", "Maugis1992", "article", "D. Maugis",
       "Adhesion of spheres: the JKR-DMT transition using a Dugdale model",
       "Journal of Colloid and Interface Science", 1992, "150", "243-269",
       "10.1016/0021-9797(92)90285-T",
       used_for="the JKR-DMT transition and the Tabor parameter's ranges"),
    _s("K71", "Kendall1971", "article", "K. Kendall",
       "The adhesion and surface energy of elastic solids",
       "Journal of Physics D: Applied Physics", 1971, "4", "1186-1195",
       "10.1088/0022-3727/4/8/320", used_for="adhesive flat punch (detachment)"),
    _s("Cat38", "Cattaneo1938", "article", "C. Cattaneo",
       "Sul contatto di due corpi elastici: distribuzione locale degli sforzi",
       "Rendiconti dell'Accademia Nazionale dei Lincei", 1938, "27", "342-348, 434-436, 474-478",
       used_for="partial slip under a tangential load (stick zone, slip annulus)"),
    _s("Min49", "Mindlin1949", "article", "R. D. Mindlin", "Compliance of elastic bodies in contact",
       "Journal of Applied Mechanics", 1949, "16", "259-268",
       used_for="tangential compliance and partial slip of spheres"),
    _s("MD53", "Mindlin1953", "article", "R. D. Mindlin, H. Deresiewicz",
       "Elastic spheres in contact under varying oblique forces",
       "Journal of Applied Mechanics", 1953, "20", "327-344",
       used_for="unloading and reloading (Masing rule), energy dissipated per cycle"),
    _s("RS44", "Reissner1944", "article", "E. Reissner, H. F. Sagoci",
       "Forced torsional oscillations of an elastic half-space. I",
       "Journal of Applied Physics", 1944, "15", "652-654",
       used_for="no-slip torsion of a circular punch: M = (16/3) G a^3 phi"),
    _s("J95", "Jaeger1995", "article", "J. Jäger",
       "Axi-symmetric bodies of equal material in contact under torsion or shift",
       "Archive of Applied Mechanics", 1995, "65", "478-487",
       used_for="exact partial-slip torsion by superposition of twisted flat punches"),
    _s("L51", "Lubkin1951", "article", "J. L. Lubkin", "The torsion of elastic spheres in contact",
       "Journal of Applied Mechanics", 1951, "18", "183-187",
       used_for="torsion of Hertzian contacts with partial slip (reference values)"),
    _s("D54", "Deresiewicz1954", "article", "H. Deresiewicz",
       "Contact of elastic spheres under an oscillating torsional couple",
       "Journal of Applied Mechanics", 1954, "21", "52-56",
       used_for="torsional hysteresis of spheres (cube law of the dissipated energy)"),
    _s("LR60", "LeeRadok1960", "article", "E. H. Lee, J. R. M. Radok",
       "The contact problem for viscoelastic bodies", "Journal of Applied Mechanics", 1960,
       "27", "438-444", used_for="viscoelastic indentation with a growing contact"),
    _s("T66", "Ting1966", "article", "T. C. T. Ting",
       "The contact stresses between a rigid indenter and a viscoelastic half-space",
       "Journal of Applied Mechanics", 1966, "33", "845-854",
       used_for="viscoelastic indentation with a shrinking contact"),
    _s("VS88", "Vingsbo1988", "article", "O. Vingsbo, S. Söderberg", "On fretting maps",
       "Wear", 1988, "126", "131-147", "10.1016/0043-1648(88)90134-2",
       used_for="fretting regimes: stick, partial slip, gross slip"),
    _s("F96", "Fouvry1996", "article", "S. Fouvry, P. Kapsa, L. Vincent",
       "Quantification of fretting damage", "Wear", 1996, "200", "186-205",
       used_for="energy ratio A = W/(4 x* y*) and its partial/gross slip transition"),
    _s("D14", "Dimaki2014", "article", "A. V. Dimaki, A. I. Dmitriev, Y. S. Chai, V. L. Popov",
       "Rapid simulation procedure for fretting wear on the basis of the method of "
       "dimensionality reduction", "International Journal of Solids and Structures", 2014,
       "51", "4215-4220", used_for="fretting wear with the MDR (Archard law, worn profile)"),
])

#: Sources per computation: (effect or model) -> tags. Drivers combine these for their results.
EFFECT_SOURCES: dict[str, tuple[str, ...]] = {
    "mdr": ("PH", "H1"),
    "normal": ("PH", "H1", "Sn65"),
    "adhesion": ("Heß11", "JKR71"),
    "adhesion:flat_punch": ("K71",),
    "tangential": ("Cat38", "Min49"),
    "masing:tangential": ("MD53",),
    "torsion:no-slip": ("RS44",),
    "torsion:exact": ("J95", "RS44"),
    "torsion:mdr": ("S", "RS44"),
    "masing:torsion": ("D54", "MD53"),
    "viscoelastic": ("H3", "LR60", "T66"),
    "foundation": ("PH", "H1"),
    "foundation:torsion": ("S",),
    "fretting": ("VS88", "F96"),
    "wear": ("D14",),
}


class Cited:
    """Mixin of the result objects: ``.citations`` from ``meta["citations"]``."""

    @property
    def citations(self) -> "Citations":
        """The sources this result's computation used (:class:`~contactlab.citations.Citations`);
        ``contactlab.cite(result)`` prints them as text and BibTeX."""
        meta = getattr(self, "meta", None) or {}
        return Citations(meta.get("citations", ()))


class Citations(tuple):
    """The sources of a result: a tuple of :class:`Source` (no duplicates, in first-use order).

    ``.tags`` gives the tags, ``str()`` the text references, :meth:`bibtex` the BibTeX entries.
    """

    def __new__(cls, tags: Iterable[str] = ()) -> "Citations":
        seen: dict[str, Source] = {}
        for t in tags:
            if t not in SOURCES:
                raise UnknownNameError(f"citation tag {t!r} is unknown: known tags are "
                                       f"{', '.join(sorted(SOURCES))}.")
            seen.setdefault(t, SOURCES[t])
        return super().__new__(cls, seen.values())

    @property
    def tags(self) -> tuple[str, ...]:
        """The tags, e.g. ``('PH', 'H1', 'J95')``."""
        return tuple(s.tag for s in self)

    def text(self) -> str:
        """One line per source."""
        return "\n".join(s.text() for s in self)

    def bibtex(self) -> str:
        """BibTeX entries, separated by blank lines."""
        return "\n\n".join(s.bibtex() for s in self)

    def __str__(self) -> str:
        return self.text()

    def __add__(self, other: Iterable[Any]) -> "Citations":
        return Citations([*self.tags, *(getattr(s, "tag", s) for s in other)])


def sources_for(*computations: str) -> tuple[str, ...]:
    """Tags of the sources of the named computations (keys of :data:`EFFECT_SOURCES`).

    Unknown computation names raise :class:`~contactlab.errors.UnknownNameError`.
    """
    tags: list[str] = []
    for name in computations:
        if name not in EFFECT_SOURCES:
            raise UnknownNameError(f"computation {name!r} has no recorded sources: known are "
                                   f"{', '.join(sorted(EFFECT_SOURCES))}.")
        tags += [t for t in EFFECT_SOURCES[name] if t not in tags]
    return tuple(tags)


def _citations_of(obj: Any) -> Citations:
    if obj is None:
        return Citations(("PH", "H1"))
    if isinstance(obj, Citations):
        return obj
    if isinstance(obj, str):
        return Citations((obj,))
    cit = getattr(obj, "citations", None)
    if cit is None:
        meta = getattr(obj, "meta", None)
        cit = meta.get("citations") if isinstance(meta, dict) else None
    if cit is None:
        if isinstance(obj, (list, tuple)):
            return Citations([t for o in obj for t in _citations_of(o).tags])
        raise ParameterError(f"cite({type(obj).__name__}) is invalid: give a contactlab result "
                             "(it has .citations), a source tag such as 'J95', or nothing (the "
                             "MDR itself).")
    return cit if isinstance(cit, Citations) else Citations(cit)


def cite(obj: Any = None, *, format: str = "both", file: IO[str] | None = sys.stdout) -> str:
    """Print (and return) the references a result relied on.

    Parameters
    ----------
    obj : result, str, list or None
        A contactlab result (anything with ``.citations``), a source tag such as ``"J95"``, a
        list of these, or ``None`` for the method itself (the MDR monograph and handbook).
    format : {"both", "text", "bibtex"}
        Text references, BibTeX entries, or both (text first).
    file : file-like or None
        Where to print; ``None`` prints nothing (the string is still returned).

    Returns
    -------
    str
        What was printed.

    Raises
    ------
    ParameterError
        ``obj`` records no citations or ``format`` is unknown.
    UnknownNameError
        An unknown source tag.
    """
    if format not in ("both", "text", "bibtex"):
        raise ParameterError(f"format={format!r} is invalid: use 'both', 'text' or 'bibtex'.")
    cits = _citations_of(obj)
    parts = []
    if format in ("both", "text"):
        parts.append("This computation relied on:\n" + cits.text())
    if format in ("both", "bibtex"):
        parts.append(cits.bibtex())
    out = "\n\n".join(parts)
    if file is not None:
        print(out, file=file)
    return out


def bibliography_markdown() -> str:
    """The bibliography page of the documentation (docs/about/references.md), generated from
    :data:`SOURCES`; a test keeps the committed page equal to this text."""
    lines = ["# References", "",
             "Every source tag used in contactlab's docstrings and documentation (written like "
             "`[J95]`) is listed here. Results list the sources their computation used in "
             "`result.citations`; `contactlab.cite(result)` prints them as text and BibTeX.",
             "This page is generated by `contactlab.citations.bibliography_markdown()`.", ""]
    for s in sorted(SOURCES.values(), key=lambda s: (s.year, s.tag)):
        lines += [f"({s.key})=", f"**[{s.tag}]** {s.text().split('] ', 1)[1]}", ""]
        if s.used_for:
            lines += [f"  *Used for:* {s.used_for}.", ""]
    return "\n".join(lines).rstrip() + "\n"
