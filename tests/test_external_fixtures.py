"""The external fixtures ship with the repository, byte for byte as documented in their README."""
import hashlib

import pytest

from helpers import EXTERNAL

SHA256 = {
    "dxf/WM_LOOSE_SHAPE_TANK_AAMA.DXF": "88dd21d6f57bd2f04b425e52abfec559435afb66aef35ea3408715c37cf099bd",
    "dxf/clo-box_R10.dxf": "404e72a9e0a11f51d89a0260dba77100c746f2e1e2e694fba080336d6c496b0b",
    "dxf/clo-pattern_R10.dxf": "75ab960c8eb939a7e91dabdf724e80b035997d881887cc4832ac764d0b61b37b",
    "dxf/ezdxf_forms_R2018_LWPOLYLINE.dxf": "7c0c39cb3fadc19dfbc6e63a5a5598393ac2007bf2ee5c2b8afc6863d4b78cef",
    "dxf/ezdxf_no_layouts_R2007_SPLINE.dxf": "65d1a55530a617de9e4333ef44b38617971ccd387b15512f6dc3eb16e71eac8a",
    "embroidery/Star.DST": "2a25d008514fa47b2fe435deacb3c8baee2ea021a3115a112cee6d7ccb912421",
    "embroidery/Star.EXP": "54c9da74d4485dea7b7feb0e2c2a51d9a3013d72ed1757ead82ed90c2ade77e1",
    "embroidery/Star.JEF": "b92574cb20a0a7af817e8b03c72ede9d71c5626f155483dd0fef40d2ab786b49",
    "embroidery/Star.pes": "31173454aa16c73af70faa3110b2bd3de8310e61131058fd4d7c5308f1c91662",
}


@pytest.mark.parametrize("name", sorted(SHA256))
def test_fixture_is_the_documented_file(name):
    assert hashlib.sha256((EXTERNAL / name).read_bytes()).hexdigest() == SHA256[name]


def test_every_fixture_has_provenance_and_licence():
    readme = (EXTERNAL / "README.md").read_text()
    shipped = {str(p.relative_to(EXTERNAL)) for p in EXTERNAL.glob("*/*") if p.parent.name != "licenses"}
    assert shipped == set(SHA256)
    for name in SHA256:
        assert f"| {name} |" in readme
    for licence in ("ISC-astm-parser.txt", "MIT-ezdxf.txt", "zlib-Embroidermodder.txt"):
        assert (EXTERNAL / "licenses" / licence).is_file()
