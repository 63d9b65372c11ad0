import pytest

from velplan.errors import VelplanError
from velplan.render.i18n import LANGUAGES, label, label_keys


@pytest.mark.parametrize("lang, text", [
    ("en", "Velocity plan"), ("ru", "План скоростей"), ("uk", "План швидкостей"),
    ("zh", "速度多边形")])
def test_velocity_plan_in_every_language(lang, text):
    assert label("velocity_plan", lang) == text


def test_acceleration_plan():
    assert label("acceleration_plan", "ru") == "План ускорений"
    assert label("acceleration_plan", "zh") == "加速度多边形"


def test_every_key_has_every_language():
    for key in label_keys():
        assert all(label(key, lang) for lang in LANGUAGES)
    for key in ("scale", "position", "title_mechanism", "table_transfer", "pole", "designed",
                "checked", "sheet", "sheets", "mass", "scale_label"):
        assert key in label_keys()


def test_unknown_language_lists_known_ones():
    with pytest.raises(VelplanError, match=r"^unknown language 'de'; known languages: "
                                           r"en, ru, uk, zh$"):
        label("pole", "de")


def test_unknown_key():
    with pytest.raises(VelplanError, match="unknown label key 'polo'; known keys: .*pole"):
        label("polo", "en")
