"""Fonts of the drawings: the bundled Velplan Sans, made visible to cairo and matplotlib, and
the check that every character of a drawing has a glyph in the font that renders it.

cairosvg draws each ``<text>`` with one font: the first family of its ``font-family`` list,
matched by fontconfig through cairo's "toy" text API, which has no fallback — a character
that font lacks is drawn as its empty box (the ``.notdef`` glyph, "tofu"), and nothing
fails. So before a sheet goes to cairosvg, :meth:`CairoFonts.choose_family` walks the list
as a browser would, with Velplan Sans before the generic names, and picks for each text the
first family that is installed and whose font has all of its characters, as cairo itself
reports them; a text no family covers is an error, not a PNG of boxes.

Velplan Sans (``velplan/fonts/VelplanSans-Regular.ttf``, SIL OFL 1.1) is Noto Sans CJK SC
cut to the characters velplan prints and to GB 2312's 6763 Chinese characters, with
Ukrainian letters, indices and ⌀ from Source Sans 3; :func:`register_with_fontconfig` adds
its directory to the fontconfig configuration cairo uses (no file to install, nothing in
the environment), :func:`register_with_matplotlib` to matplotlib's font manager.
"""

from __future__ import annotations

import ctypes
import functools
import os
from pathlib import Path

#: Family name of the bundled font.
BUNDLED_FAMILY = "Velplan Sans"
#: The bundled font file.
BUNDLED_FONT = Path(__file__).resolve().parents[1] / "fonts" / "VelplanSans-Regular.ttf"
#: CSS generic family names: resolved by the renderer, tried after the bundled font.
GENERIC_FAMILIES = frozenset({"serif", "sans-serif", "cursive", "fantasy", "monospace",
                              "system-ui"})
# Names under which the fontconfig library that cairo loaded can be opened again.
_FONTCONFIG_LIBRARIES = ("libfontconfig.so.1", "libfontconfig.1.dylib", "libfontconfig-1.dll",
                         "libfontconfig.so")
# Glyphs are looked up and measured at this size, unhinted, and scaled.
_MEASURE_SIZE = 100.0


@functools.cache
def bundled_coverage() -> frozenset[int]:
    """Code points the bundled font has glyphs for (its cmap, read with fontTools)."""
    from fontTools.ttLib import TTFont

    with TTFont(str(BUNDLED_FONT), lazy=True) as font:
        return frozenset(font.getBestCmap())


def missing_in_bundled(text: str) -> str:
    """The characters of `text` the bundled font lacks, each once, in order of appearance.

    White space is never missing: renderers skip it.

    Examples
    --------
    >>> missing_in_bundled("速度多边形 V₂, м/с²")
    ''
    """
    covered = bundled_coverage()
    return "".join(dict.fromkeys(c for c in text if not c.isspace() and ord(c) not in covered))


def css_families(value: str | None) -> list[str]:
    """The family names of a CSS ``font-family`` value, unquoted, in order.

    Examples
    --------
    >>> css_families("'Noto Sans CJK SC', SimHei, sans-serif")
    ['Noto Sans CJK SC', 'SimHei', 'sans-serif']
    """
    names = (part.strip().strip("'\"").strip() for part in (value or "").split(","))
    return [name for name in names if name]


def candidate_families(families: list[str]) -> list[str]:
    """The families to try, in order: the named ones, Velplan Sans (where the list names
    it, else after them), then the generic ones.

    Examples
    --------
    >>> candidate_families(["DejaVu Sans", "sans-serif"])
    ['DejaVu Sans', 'Velplan Sans', 'sans-serif']
    """
    named = [f for f in families if f.lower() not in GENERIC_FAMILIES]
    generic = [f for f in families if f.lower() in GENERIC_FAMILIES]
    if BUNDLED_FAMILY not in named:
        named.append(BUNDLED_FAMILY)
    return named + (generic or ["sans-serif"])


def register_with_fontconfig() -> bool:
    """Make the bundled font visible to cairo: add its directory to fontconfig's current
    configuration (``FcConfigAppFontAddDir``, about 5 ms) unless fontconfig lists it
    already. Works before or after cairo first used a font; False where no fontconfig
    library can be opened (cairo's Windows and macOS font backends do not use it)."""
    library = _fontconfig_library()
    if library is None:
        return False
    if installed(BUNDLED_FAMILY):
        return True
    add_dir = library.FcConfigAppFontAddDir
    add_dir.argtypes, add_dir.restype = [ctypes.c_void_p, ctypes.c_char_p], ctypes.c_int
    return bool(add_dir(None, os.fsencode(BUNDLED_FONT.parent))) and bool(
        installed(BUNDLED_FAMILY))


@functools.cache
def _fontconfig_library():
    """The fontconfig library (the one cairo loaded, where it did), or None."""
    for name in _FONTCONFIG_LIBRARIES:
        try:
            return ctypes.CDLL(name)
        except OSError:
            continue
    return None


class _FcFontSet(ctypes.Structure):
    _fields_ = [("nfont", ctypes.c_int), ("sfont", ctypes.c_int), ("fonts", ctypes.c_void_p)]


def installed(family: str) -> bool | None:
    """Whether fontconfig has a font of `family` (by name, not a substitute for it): True,
    False, or None where fontconfig cannot be asked. The bundled font counts once
    registered."""
    library = _fontconfig_library()
    if library is None:
        return None
    fc = _fontconfig_functions(library)
    pattern, objects = fc.FcPatternCreate(), fc.FcObjectSetCreate()
    try:
        fc.FcPatternAddString(pattern, b"family", family.encode("utf-8"))
        fc.FcObjectSetAdd(objects, b"family")
        fonts = fc.FcFontList(None, pattern, objects)
        if not fonts:
            return False
        count = fonts.contents.nfont
        fc.FcFontSetDestroy(fonts)
        return count > 0
    finally:
        fc.FcObjectSetDestroy(objects)
        fc.FcPatternDestroy(pattern)


@functools.cache
def _fontconfig_functions(library):
    """`library` with the signatures of the fontconfig functions :func:`installed` calls."""
    pointer = ctypes.c_void_p
    for name, argtypes, restype in (
            ("FcPatternCreate", [], pointer),
            ("FcPatternAddString", [pointer, ctypes.c_char_p, ctypes.c_char_p], ctypes.c_int),
            ("FcObjectSetCreate", [], pointer),
            ("FcObjectSetAdd", [pointer, ctypes.c_char_p], ctypes.c_int),
            ("FcFontList", [pointer, pointer, pointer], ctypes.POINTER(_FcFontSet)),
            ("FcFontSetDestroy", [ctypes.POINTER(_FcFontSet)], None),
            ("FcObjectSetDestroy", [pointer], None),
            ("FcPatternDestroy", [pointer], None)):
        function = getattr(library, name)
        function.argtypes, function.restype = argtypes, restype
    return library


@functools.cache
def register_with_matplotlib() -> str:
    """Add the bundled font to matplotlib's font manager; return its family name."""
    from matplotlib import font_manager

    font_manager.fontManager.addfont(str(BUNDLED_FONT))
    return BUNDLED_FAMILY


class CairoFonts:
    """What cairo's toy text API — the one cairosvg draws with — makes of font families.

    Parameters
    ----------
    cairo : module
        ``cairocffi`` (as cairosvg imports it).

    Notes
    -----
    A character whose glyph index is 0 is drawn as ``.notdef``: the family's font, as
    fontconfig matches it, lacks it. Answers are cached per family, style and character,
    for the life of the object (one conversion: fonts may be installed meanwhile).
    """

    def __init__(self, cairo) -> None:
        self._cairo = cairo
        self._context = cairo.Context(cairo.ImageSurface(cairo.FORMAT_ARGB32, 1, 1))
        options = cairo.FontOptions()
        options.set_hint_metrics(cairo.HINT_METRICS_OFF)
        options.set_hint_style(cairo.HINT_STYLE_NONE)
        self._context.set_font_options(options)
        self._glyphs: dict[tuple[str, bool], dict[str, tuple[int, float]]] = {}
        self._installed: dict[str, bool | None] = {}

    def missing(self, family: str, text: str, *, italic: bool = False) -> str:
        """The characters of `text` that `family` draws as ``.notdef``, each once."""
        glyphs = self._lookup(family, italic, text)
        return "".join(dict.fromkeys(c for c in text if not c.isspace() and glyphs[c][0] == 0))

    def advance(self, family: str, text: str, size: float, *, italic: bool = False) -> float:
        """Width of `text` at font size `size` (user units) as cairosvg lays it out: the sum
        of its characters' advances."""
        glyphs = self._lookup(family, italic, text)
        return sum(glyphs[c][1] for c in text) * size / _MEASURE_SIZE

    def _lookup(self, family: str, italic: bool, text: str) -> dict[str, tuple[int, float]]:
        """Glyph index and advance (at the measuring size) of each character of `text`."""
        known = self._glyphs.setdefault((family, italic), {})
        new = [c for c in dict.fromkeys(text) if c not in known]
        if new:
            cairo, context = self._cairo, self._context
            slant = cairo.FONT_SLANT_ITALIC if italic else cairo.FONT_SLANT_NORMAL
            context.select_font_face(family, slant, cairo.FONT_WEIGHT_NORMAL)
            context.set_font_size(_MEASURE_SIZE)
            font = context.get_scaled_font()
            for char in new:
                glyph = font.text_to_glyphs(0, 0, char, False)
                index = glyph[0][0] if len(glyph) == 1 else 0
                known[char] = (index, font.text_extents(char)[4])
        return known

    def choose_family(self, families: list[str], text: str, *,
                      italic: bool = False) -> str | None:
        """The first of :func:`candidate_families` that is installed (a named family that
        fontconfig lacks would be drawn with a substitute) and whose font has every
        character of `text`; None if there is none."""
        for family in self.usable(families):
            if not self.missing(family, text, italic=italic):
                return family
        return None

    def usable(self, families: list[str]) -> list[str]:
        """:func:`candidate_families` less the named families fontconfig does not have."""
        usable = []
        for family in candidate_families(families):
            if family not in self._installed:
                self._installed[family] = installed(family)
            if family.lower() in GENERIC_FAMILIES or self._installed[family] is not False:
                usable.append(family)
        return usable
