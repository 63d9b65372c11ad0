"""``python -m velplan.render.fontbuild CJK SANS [-o FILE]``: remake the bundled Velplan Sans.

Not imported by velplan at run time; it documents, and repeats, how the bundled
``VelplanSans-Regular.ttf`` was made (fontTools only, no network):

* ``CJK``: ``NotoSansCJK-VF.otf.ttc`` (Noto Sans CJK 2.004, the variable collection, as
  shipped in the PyPI wheel ``manimgx-fonts-cjk==2026.9.26.post1``); its face
  "Noto Sans CJK SC" gives Chinese (simplified forms), Latin, Greek, basic Cyrillic and the
  symbols.
* ``SANS``: ``SourceSans3[wght].ttf`` (Source Sans 3.052, from the PyPI wheel
  ``fontpkg-source-sans-3==3.52``), the Latin design Noto Sans CJK's own Latin is drawn
  from; scaled to the same capital height, it fills in what the CJK face lacks (Ukrainian
  and other Cyrillic letters, sub- and superscripts, modifier letters) and gives the
  proportional forms of the symbols the CJK face sets one em wide (·, ±, ≥, quotes,
  arrows).

Both are set at weight 400 and cut to the characters velplan can print: every label of
:mod:`velplan.render.i18n`, the Chinese names in the bundled mechanism files, the 6763
Chinese characters of GB 2312 (everyday Chinese, for titles users type), Latin, Greek,
Cyrillic, punctuation, arrows, mathematical and technical signs. The diameter sign ⌀, which
neither font has, is drawn with the CJK face's ∅. Outlines are converted to TrueType
(quadratic, within 1 unit of 1000), so that cairo, browsers and matplotlib's PDF backend
all embed the font; layout tables are dropped (cairo's toy text API does not use them).
The result is renamed "Velplan Sans" (OFL: a modified font must not keep a reserved name
— 'Source' is one — and a distinct name keeps fontconfig from mixing it up with an
installed Noto Sans CJK). The same sources give the same bytes (fixed timestamps).

Getting the sources::

    pip download --no-deps -d src manimgx-fonts-cjk==2026.9.26.post1 fontpkg-source-sans-3==3.52
    cd src && for w in *.whl; do python -m zipfile -e "$w" .; done
    python -m velplan.render.fontbuild manimgx_fonts_cjk/NotoSansCJK-VF.otf.ttc \
        "fontpkg_source_sans_3/files/SourceSans3[wght].ttf"

Setting the CJK face at weight 400 takes about half a minute (it is cut first).
"""

from __future__ import annotations

import argparse
import re
import sys
import unicodedata
from pathlib import Path
from typing import NamedTuple

FAMILY = "Velplan Sans"
#: The bundled font file (``velplan/fonts/``).
DEFAULT_OUTPUT = Path(__file__).resolve().parents[1] / "fonts" / "VelplanSans-Regular.ttf"
#: Fixed timestamps (seconds since 1904) keep the build byte-for-byte repeatable.
_TIMESTAMP = 3_800_000_000

#: Unicode ranges kept, inclusive: Latin, Greek, Cyrillic, modifier letters, punctuation,
#: super- and subscripts, letterlike symbols, arrows, mathematical and technical signs,
#: geometric shapes, CJK punctuation and full-width forms.
RANGES: tuple[tuple[int, int], ...] = (
    (0x0020, 0x007E), (0x00A0, 0x024F), (0x02B0, 0x02FF), (0x0370, 0x03FF),
    (0x0400, 0x052F), (0x1D2C, 0x1D6A), (0x1D9B, 0x1DBF), (0x2010, 0x205E), (0x2070, 0x209C),
    (0x2100, 0x214F), (0x2190, 0x21FF), (0x2200, 0x22FF), (0x2300, 0x23FF),
    (0x25A0, 0x25FF), (0x3000, 0x303F), (0xFF01, 0xFF5E), (0xFFE0, 0xFFE6),
)
_DIAMETER, _EMPTY_SET = 0x2300, 0x2205
_CJK_IDEOGRAPH = re.compile(r"[\u3400-\u9fff\uf900-\ufaff]")


def gb2312_hanzi() -> str:
    """The 6763 Chinese characters of GB 2312 (rows 16–87), decoded by Python's codec."""
    chars = []
    for high in range(0xB0, 0xF8):
        for low in range(0xA1, 0xFF):
            try:
                chars.append(bytes((high, low)).decode("gb2312"))
            except UnicodeDecodeError:
                continue
    return "".join(chars)


def label_characters() -> str:
    """Every character of every drawing label, in every language."""
    from velplan.render.i18n import LANGUAGES, label, label_keys

    return "".join(label(key, lang) for key in label_keys() for lang in LANGUAGES)


def data_characters() -> str:
    """The Chinese characters written in the bundled mechanism files (their zh names)."""
    root = Path(__file__).resolve().parents[1]
    text = "".join(p.read_text(encoding="utf-8")
                   for folder in ("examples", "catalogue") for p in (root / folder).glob("*.toml"))
    return "".join(_CJK_IDEOGRAPH.findall(text))


def wanted_codepoints() -> set[int]:
    """Code points the bundled font should cover (where a source font has them)."""
    wanted = {cp for first, last in RANGES for cp in range(first, last + 1)}
    wanted |= {ord(c) for c in gb2312_hanzi() + label_characters() + data_characters()}
    return wanted


def open_face(path: Path, family: str | None = None):
    """One face of a font file or collection, by its family name (name ID 1)."""
    from fontTools.ttLib import TTCollection, TTFont

    if path.suffix.lower() in (".ttc", ".otc") or path.name.endswith(".ttc"):
        faces = TTCollection(str(path)).fonts
        for face in faces:
            if face["name"].getDebugName(1) == family:
                return face
        raise SystemExit(f"{path}: no face named {family!r}")
    return TTFont(str(path))


def regular_subset(font, codepoints: set[int]):
    """`font` cut to `codepoints` (outlines only), then set at weight 400 if variable."""
    from fontTools import subset
    from fontTools.varLib import instancer

    options = subset.Options()
    options.layout_features = []
    options.hinting = False
    options.notdef_outline = True
    # HVAR and MVAR stay: they carry the advance widths and metrics at weight 400.
    options.drop_tables += ["GSUB", "GPOS", "GDEF", "BASE", "VORG", "vhea", "vmtx", "VVAR",
                            "STAT", "DSIG", "meta"]
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=sorted(codepoints & set(font.getBestCmap())))
    subsetter.subset(font)
    if "fvar" in font:
        _drop_empty_private_values(font)
        font = instancer.instantiateVariableFont(font, {"wght": 400})
    return font


def _drop_empty_private_values(font) -> None:
    """Delete the CFF2 private-dict entries the subsetter left as None (the instancer trips
    over them)."""
    from fontTools.cffLib import privateDictOperators2

    if "CFF2" not in font:
        return
    names = {entry[1] for entry in privateDictOperators2}
    for fd in getattr(font["CFF2"].cff.topDictIndex[0], "FDArray", []):
        private = fd.Private
        for name in [k for k, v in vars(private).items() if v is None and k in names]:
            delattr(private, name)


class Source(NamedTuple):
    """A source font as the merge uses it.

    Attributes
    ----------
    font : TTFont
        The font, cut and set at weight 400.
    cubic : bool
        True for PostScript (CFF) outlines, which are converted and reversed.
    scale : float
        Factor applied to its outlines and advances: Source Sans is drawn 11 % larger, so
        that its capitals are as tall as Noto Sans CJK's (733 units, against 660).
    """

    font: object
    cubic: bool
    scale: float


def _truetype_glyph(source: Source, name: str):
    """Glyph `name` of `source` as a TrueType glyph (components decomposed, scaled)."""
    from fontTools.pens.cu2quPen import Cu2QuPen
    from fontTools.pens.recordingPen import DecomposingRecordingPen
    from fontTools.pens.transformPen import TransformPen
    from fontTools.pens.ttGlyphPen import TTGlyphPen

    glyph_set = source.font.getGlyphSet()
    recording = DecomposingRecordingPen(glyph_set)
    glyph_set[name].draw(recording)
    pen = TTGlyphPen(None)
    target = Cu2QuPen(pen, max_err=1.0, reverse_direction=source.cubic)
    recording.replay(TransformPen(target, (source.scale, 0, 0, source.scale, 0, 0)))
    return pen.glyph()


def _full_width_symbol(cjk: Source, cp: int) -> bool:
    """True where the CJK face draws a Latin-context symbol (·, ±, ≥, quotes, arrows…) one
    em wide, as Chinese text sets it: a drawing wants the proportional form."""
    name = cjk.font.getBestCmap().get(cp)
    return (name is not None and cjk.font["hmtx"][name][0] >= 1000
            and unicodedata.east_asian_width(chr(cp)) not in ("W", "F"))


def merged_glyphs(cjk: Source, sans: Source, codepoints: set[int]) -> dict[int, tuple]:
    """Code point → (source, glyph name): the CJK face, except where it lacks the character
    or sets a symbol full-width and Source Sans has it."""
    chosen: dict[int, tuple] = {}
    sans_cmap = sans.font.getBestCmap()
    for cp, name in cjk.font.getBestCmap().items():
        if cp in codepoints:
            chosen[cp] = (cjk, name)
    for cp in codepoints & set(sans_cmap):
        if cp not in chosen or _full_width_symbol(cjk, cp):
            chosen[cp] = (sans, sans_cmap[cp])
    cjk_cmap = cjk.font.getBestCmap()
    if _DIAMETER not in chosen and _EMPTY_SET in cjk_cmap:
        chosen[_DIAMETER] = (cjk, cjk_cmap[_EMPTY_SET])
    return chosen


def build(cjk_path: Path, sans_path: Path):
    """The Velplan Sans font (a fontTools TTFont) from the two source files."""
    from fontTools.fontBuilder import FontBuilder

    codepoints = wanted_codepoints()
    cjk_font = regular_subset(open_face(cjk_path, "Noto Sans CJK SC"), codepoints)
    sans_font = regular_subset(open_face(sans_path), codepoints)
    cjk = Source(cjk_font, True, 1.0)
    sans = Source(sans_font, False, cjk_font["OS/2"].sCapHeight / sans_font["OS/2"].sCapHeight)
    chosen = merged_glyphs(cjk, sans, codepoints)
    order = [".notdef"] + [f"uni{cp:04X}" if cp < 0x10000 else f"u{cp:05X}"
                           for cp in sorted(chosen)]
    glyphs = {".notdef": _truetype_glyph(cjk, ".notdef")}
    advances = {".notdef": cjk_font["hmtx"][".notdef"][0]}
    for name, cp in zip(order[1:], sorted(chosen)):
        source, glyph = chosen[cp]
        glyphs[name] = _truetype_glyph(source, glyph)
        advances[name] = round(source.font["hmtx"][glyph][0] * source.scale)
    builder = FontBuilder(1000, isTTF=True)
    builder.setupGlyphOrder(order)
    builder.setupCharacterMap({cp: name for name, cp in zip(order[1:], sorted(chosen))})
    builder.setupGlyf(glyphs)
    glyf = builder.font["glyf"]
    builder.setupHorizontalMetrics({n: (advances[n], getattr(glyf[n], "xMin", 0))
                                    for n in order})
    hhea, os2 = cjk_font["hhea"], cjk_font["OS/2"]
    builder.setupHorizontalHeader(ascent=hhea.ascent, descent=hhea.descent)
    builder.setupNameTable(_names(cjk_font, sans_font))
    builder.setupOS2(sTypoAscender=os2.sTypoAscender, sTypoDescender=os2.sTypoDescender,
                     sTypoLineGap=0, usWinAscent=os2.usWinAscent,
                     usWinDescent=os2.usWinDescent, sxHeight=os2.sxHeight,
                     sCapHeight=os2.sCapHeight, achVendID="VLPN", fsType=0,
                     usWeightClass=400)
    builder.setupPost(keepGlyphNames=False)
    font = builder.font
    font["OS/2"].recalcUnicodeRanges(font)
    font["head"].created = font["head"].modified = _TIMESTAMP
    return font


def _names(cjk, sans) -> dict[str, str]:
    """Name table of the merged font: new names, the sources' copyrights, the licence."""
    return {
        "familyName": FAMILY,
        "styleName": "Regular",
        "uniqueFontIdentifier": f"{FAMILY} Regular 1.0",
        "fullName": f"{FAMILY} Regular",
        "psName": "VelplanSans-Regular",
        "version": "Version 1.000",
        "copyright": f"{cjk['name'].getDebugName(0)} {sans['name'].getDebugName(0)}",
        "description": "Noto Sans CJK SC 2.004 and Source Sans 3.052, weight 400, cut to "
                       "the characters of velplan's drawings and GB 2312",
        "licenseDescription": "This Font Software is licensed under the SIL Open Font "
                              "License, Version 1.1.",
        "licenseInfoURL": "https://openfontlicense.org",
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m velplan.render.fontbuild",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("cjk", type=Path, help="NotoSansCJK-VF.otf.ttc")
    parser.add_argument("sans", type=Path, help="SourceSans3[wght].ttf")
    parser.add_argument("-o", "--output", type=Path, default=DEFAULT_OUTPUT)
    args = parser.parse_args(argv)
    font = build(args.cjk, args.sans)
    font.save(str(args.output))
    sys.stdout.write(f"wrote {args.output}: {len(font.getGlyphOrder())} glyphs, "
                     f"{args.output.stat().st_size} bytes\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
