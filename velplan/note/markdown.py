"""The note as pandoc Markdown (TeX math), for one target: ``"md"`` (the file written for
readers), ``"docx"``, ``"typst"`` or ``"html"`` (the source pandoc converts; raw blocks carry
what Markdown cannot say: the title page, the contents, page breaks)."""

from __future__ import annotations

import re
from html import escape as html_escape

from velplan.note.blocks import Contents, Equation, Figure, Heading, Math, PageBreak, Para, Table, TitlePage


def xml_escape(s: str) -> str:
    """``&``, ``<`` and ``>`` escaped for XML text (as `xml.sax.saxutils.escape`, whose import
    brings urllib.request, http.client and email)."""
    return html_escape(s, quote=False)


_MD_SPECIAL = re.compile(r"([\\*_$\[\]<>#^~|`@])")
_TYP_SPECIAL = re.compile(r"([\\#\[\]*_$<>@~`'\"/=+-])")


def md_text(s: str) -> str:
    """Plain text safe in pandoc Markdown."""
    return _MD_SPECIAL.sub(r"\\\1", s)


def typ_text(s: str) -> str:
    """Plain text safe in Typst markup."""
    return _TYP_SPECIAL.sub(r"\\\1", s)


def to_markdown(note, target: str, images: dict[str, str], *, placeholder: str | None = None) -> str:
    """The whole note; ``images`` maps a figure's name to the path the output refers to; with
    ``placeholder``, every formula is written as that TeX instead (`velplan.note.docx_math`)."""
    out = []
    for block in note.blocks:
        out.append(_block(block, note, target, images, placeholder))
    return "\n\n".join(x for x in out if x) + "\n"


def para_parts(b: Para, lang: str) -> list:
    """A paragraph's plain pieces and its `Math`, each symbol of its text a formula."""
    from velplan.note.prose import sentence_parts

    return [y for x in b.parts for y in ((x,) if isinstance(x, Math) else sentence_parts(x, lang))]


def _block(b, note, target: str, images: dict[str, str], placeholder: str | None = None) -> str:
    if isinstance(b, Heading):
        return "#" * b.level + " " + md_text(b.text) + ("" if b.numbered or target == "md" else " {-}")
    if isinstance(b, Para):
        return "".join(f"${placeholder or x.tex}$" if isinstance(x, Math) else md_text(x)
                       for x in para_parts(b, note.lang))
    if isinstance(b, Equation):
        return f"$${placeholder or b.tex}$$"
    if isinstance(b, Table):
        if target == "md":
            return f"**{md_text(b.caption)}**\n\n" + _pipe_table(b)
        return _pipe_table(b, subscripts=True) + f"\n\n: {md_text(b.caption)}"
    if isinstance(b, Figure):
        size = f"{{width={b.width_mm:.0f}mm}}" if target != "md" else ""
        return f"![{md_text(b.caption)}]({images[b.name]}){size}"
    if isinstance(b, TitlePage):
        return _title(b, target)
    if isinstance(b, Contents):
        return _contents(b, note, target)
    if isinstance(b, PageBreak):
        return {"docx": '```{=openxml}\n<w:p><w:r><w:br w:type="page"/></w:r></w:p>\n```',
                "typst": "```{=typst}\n#pagebreak(weak: true)\n```",
                "html": '```{=html}\n<div style="break-after: page"></div>\n```'}.get(target, "")
    raise TypeError(f"unknown block {b!r}")


def _pipe_table(t: Table, subscripts: bool = False) -> str:
    """A pipe table whose separator is long enough that pandoc wraps its cells to the text width,
    each column's share following its longest cell."""
    cols = len(t.header)
    widths = [max(len(str(r[c])) for r in (t.header,) + t.rows) for c in range(cols)]
    total = sum(widths)
    dashes = [max(3, round(100 * w / total)) for w in widths]

    def row(cells):
        if subscripts:  # symbols typeset (`velplan.note.cells`): pandoc's own Markdown reads ~…~
            from velplan.note.cells import cell_markdown

            return "| " + " | ".join(cell_markdown(str(c), md_text) for c in cells) + " |"
        return "| " + " | ".join(md_text(str(c)) for c in cells) + " |"

    sep = "|" + "|".join("-" * d for d in dashes) + "|"
    return "\n".join([row(t.header), sep] + [row(r) for r in t.rows])


def _title(b: TitlePage, target: str) -> str:
    people = [f"{label}: {value}" for label, value in b.fields]
    if target == "docx":
        def para(text, size=28, space=0):
            return (f'<w:p><w:pPr><w:spacing w:before="{space}"/><w:jc w:val="center"/></w:pPr><w:r><w:rPr>'
                    f'<w:sz w:val="{size}"/></w:rPr><w:t xml:space="preserve">{xml_escape(text)}</w:t></w:r></w:p>')
        body = (para(b.organisation) + para(b.kind, 40, 3000) + para(b.course) + para(b.topic, 32, 400)
                + para(b.designation, 28, 400) + "".join(para(x, 28, 200 if k else 2400) for k, x in enumerate(people))
                + para(b.place_year, 28, 2400))
        return "```{=openxml}\n" + body + "\n```"
    if target == "typst":
        lines = [f"#align(center)[#text(size: 13pt)[{typ_text(b.organisation)}]]", "#v(1fr)",
                 f"#align(center)[#text(size: 20pt)[{typ_text(b.kind)}]]",
                 f"#align(center)[#text(size: 13pt)[{typ_text(b.course)}]]", "#v(1em)",
                 f"#align(center)[#text(size: 16pt)[{typ_text(b.topic)}]]", "#v(1em)",
                 f"#align(center)[{typ_text(b.designation)}]", "#v(1fr)"]
        lines += [f"#align(right)[{typ_text(x)}]" for x in people]
        lines += ["#v(2em)", f"#align(center)[{typ_text(b.place_year)}]"]
        return "```{=typst}\n" + "\n".join(lines) + "\n```"
    if target == "html":
        parts = [b.organisation, b.kind, b.course, b.topic, b.designation] + people + [b.place_year]
        return ("```{=html}\n<div class=\"title-page\" style=\"text-align:center\">"
                + "".join(f"<p>{html_escape(x)}</p>" for x in parts) + "</div>\n```")
    return "\n\n".join(f"**{md_text(x)}**" for x in (b.organisation, b.kind, b.course, b.topic, b.designation)) \
        + "\n\n" + "\\\n".join(md_text(x) for x in people) + "\n\n" + md_text(b.place_year)


def _contents(b: Contents, note, target: str) -> str:
    if target == "docx":
        field = ('<w:p><w:r><w:fldChar w:fldCharType="begin" w:dirty="true"/></w:r><w:r><w:instrText '
                 'xml:space="preserve">TOC \\o "1-2" \\h \\z \\u</w:instrText></w:r><w:r><w:fldChar '
                 'w:fldCharType="separate"/></w:r><w:r><w:t>…</w:t></w:r><w:r><w:fldChar w:fldCharType="end"/>'
                 '</w:r></w:p>')
        head = f'<w:p><w:pPr><w:pStyle w:val="TOCHeading"/></w:pPr><w:r><w:t>{xml_escape(b.title)}</w:t></w:r></w:p>'
        return "```{=openxml}\n" + head + field + "\n```"
    if target == "typst":
        return f"```{{=typst}}\n#outline(title: [{typ_text(b.title)}], depth: 2)\n```"
    items = [("  " * (h.level - 1)) + "- " + md_text(h.text) for h in note.blocks
             if isinstance(h, Heading) and h.level <= 2]
    return f"**{md_text(b.title)}**\n\n" + "\n".join(items)
