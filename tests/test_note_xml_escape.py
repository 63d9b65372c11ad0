"""`velplan.note.markdown.xml_escape` escapes as `xml.sax.saxutils.escape` does (the .docx's
title page and contents heading are raw OpenXML)."""

from __future__ import annotations

from xml.sax.saxutils import escape

from hypothesis import given, strategies as st

from velplan.note.markdown import xml_escape


@given(st.text(alphabet=st.sampled_from("&<>\"' aωБ₁;&amp;"), max_size=40))
def test_the_same_as_saxutils(text):
    assert xml_escape(text) == escape(text)


def test_markup_characters_escaped_quotes_kept():
    assert xml_escape('Группа "А" & <Б>') == 'Группа "А" &amp; &lt;Б&gt;'
