"""The server-rendered view's channel in-process (fake server, view and image delivery): each
edit renders and pushes at once, and the image still being encoded is asked for again until
the encoder has it; where the view is drawn (``render_mode``)."""
import asyncio

import pytest

from stitchswitch.studio.view3d import image_channel, render_mode
from stitchswitch.studio.view3d.image_channel import ImageChannel


class FakeApp:
    """vtkWebApplication's encoder: an image pushed is encoded after ``encode_asks`` asks."""

    def __init__(self, encode_asks):
        self.encode_asks = encode_asks
        self.pending = 0

    def GetHasImagesBeingProcessed(self, render_window):    # noqa: N802  (VTK's name)
        return self.pending > 0


class FakeDelivery:
    """trame-vtk's image delivery: the view's ratio and quality, set as its RPC sets them."""

    def __init__(self, app):
        self.app = app
        self.pushed = []
        self.tracking_views = {"7": {"ratio": 1, "quality": 90}}
        self.settings = []

    def get_global_id(self, render_window):
        return 7

    def set_view_quality(self, view_id, quality, ratio=1):
        self.tracking_views[view_id].update(quality=quality, ratio=ratio)
        self.settings.append((quality, ratio))

    def push_render(self, view_id):
        self.pushed.append(view_id)
        self.app.pending = max(0, self.app.pending - 1)


class FakeProtocol:
    def __init__(self, delivery):
        self.delivery = delivery

    def getLinkProtocols(self):                             # noqa: N802  (wslink's name)
        return [object(), self.delivery]


class FakeServer:
    def __init__(self, protocol):
        self.protocol = protocol


class FakeView:
    """``VtkRemoteView.update``: renders, hands the frame to the encoder, pushes what is ready;
    ``ratios``: the delivery's ratio at each render (with a delivery)."""

    def __init__(self, app, delivery=None):
        self.app = app
        self.delivery = delivery
        self.updates = 0
        self.ratios = []

    def update(self):
        self.updates += 1
        self.app.pending = self.app.encode_asks
        if self.delivery is not None:
            self.ratios.append(self.delivery.tracking_views["7"]["ratio"])


def test_each_edit_pushes_its_image_as_soon_as_it_is_encoded(monkeypatch):
    app = FakeApp(encode_asks=3)
    delivery = FakeDelivery(app)
    monkeypatch.setattr(image_channel, "image_delivery", lambda protocol: delivery)
    built, sent, delivered = [], [], []

    async def run():
        view = FakeView(app)
        ch = ImageChannel(FakeServer(FakeProtocol(delivery)), view, "rw", lambda: built.append(1),
                          lambda *t: sent.append(t),
                          lambda: delivered.append(list(delivery.pushed)))
        ch.send()
        assert view.updates == 1 and built == [1] and len(sent) == 1 and ch.sent == 1
        assert delivery.pushed == [] and delivered == []    # the encoder is still busy
        await asyncio.sleep(0.1)
        # asked again until the encoder had nothing left, then no more; told once, after the
        # image went out
        assert delivery.pushed == ["7"] * 3 and ch.polls == 3
        assert delivered == [["7"] * 3]
        ch.loaded()                                 # nothing in flight: nothing happens
        ch.send()
        ch.send()                                   # a newer edit: its own frame, one poll chain
        await asyncio.sleep(0.1)
        assert view.updates == 3 and delivery.pushed == ["7"] * 6

    asyncio.run(run())


def test_a_dragged_sliders_drafts_are_followed_by_one_full_size_image(monkeypatch):
    monkeypatch.setattr(image_channel, "STILL_AFTER_S", 0.05)
    app = FakeApp(encode_asks=2)
    delivery = FakeDelivery(app)
    monkeypatch.setattr(image_channel, "image_delivery", lambda protocol: delivery)
    built, sent, delivered = [], [], []

    async def run():
        view = FakeView(app, delivery)
        ch = ImageChannel(FakeServer(FakeProtocol(delivery)), view, "rw", lambda: built.append(1),
                          lambda *t: sent.append(t), lambda: delivered.append(view.updates),
                          still_quality=90, draft_quality=70)
        for _ in range(3):                           # three steps, closer than the pause
            ch.send(draft=True)
            await asyncio.sleep(0.02)
        assert view.ratios == [image_channel.DRAFT_RATIO] * 3
        assert delivery.settings == [(70, image_channel.DRAFT_RATIO)]     # set once
        await asyncio.sleep(0.1)
        # the pause: one full-size image at still quality, of the scene already built, not an
        # edit's (no build, no timings)
        assert view.ratios[3:] == [1.0] and delivery.settings[-1] == (90, 1.0)
        assert built == [1] * 3 and len(sent) == 3 and ch.drafts == 3 and ch.sent == 4
        assert delivered == [1, 2, 3]                # once per edit
        ch.send(draft=True)
        ch.send()                                    # a full-size edit: no image due after it
        await asyncio.sleep(0.1)
        assert view.ratios[4:] == [image_channel.DRAFT_RATIO, 1.0] and ch.sent == 6

    asyncio.run(run())


def test_an_edits_image_is_told_delivered_when_the_full_size_image_overtakes_it(monkeypatch):
    monkeypatch.setattr(image_channel, "STILL_AFTER_S", 0.001)
    monkeypatch.setattr(image_channel, "MAX_POLLS", 10 ** 6)
    app = FakeApp(encode_asks=10)                   # the draft still encoding at the pause
    delivery = FakeDelivery(app)
    monkeypatch.setattr(image_channel, "image_delivery", lambda protocol: delivery)

    async def run():
        delivered = []
        view = FakeView(app, delivery)
        ch = ImageChannel(FakeServer(FakeProtocol(delivery)), view, "rw", lambda: None,
                          lambda *t: None, lambda: delivered.append(view.updates))
        ch.send(draft=True)
        await asyncio.sleep(0.5)
        assert view.ratios == [image_channel.DRAFT_RATIO, 1.0] and delivered == [2]

    asyncio.run(run())


def test_polls_stop_after_their_limit(monkeypatch):
    monkeypatch.setattr(image_channel, "MAX_POLLS", 4)
    app = FakeApp(encode_asks=10 ** 6)                # an encoder that never finishes
    delivery = FakeDelivery(app)
    monkeypatch.setattr(image_channel, "image_delivery", lambda protocol: delivery)

    async def run():
        delivered = []
        ch = ImageChannel(FakeServer(FakeProtocol(delivery)), FakeView(app), "rw", lambda: None,
                          lambda *t: None, lambda: delivered.append(ch.polls))
        ch.send()
        await asyncio.sleep(0.1)
        assert ch.polls == 4 and delivered == [4]       # given up: what waits on it goes on

    asyncio.run(run())


def test_no_page_connected_renders_nothing():
    app = FakeApp(encode_asks=1)
    view = FakeView(app)
    server = FakeServer(None)
    built = []
    delivered = []
    ch = ImageChannel(server, view, "rw", lambda: built.append(1), lambda *t: None,
                      lambda: delivered.append(1))
    ch.send()
    assert built == [1] and view.updates == 0 and ch.sent == 0 and delivered == [1]


def test_the_image_delivery_is_found_among_the_link_protocols():
    pytest.importorskip("trame_vtk")
    from trame_vtk.modules.vtk.protocols import vtkWebPublishImageDelivery

    delivery = vtkWebPublishImageDelivery(decode=False)
    assert image_channel.image_delivery(FakeProtocol(delivery)) is delivery
    assert image_channel.image_delivery(FakeProtocol(object())) is None


@pytest.mark.parametrize("name, software", [
    ("llvmpipe (LLVM 15.0.6, 256 bits)", True), ("Google SwiftShader", True),
    ("Mesa softpipe", True), ("NVIDIA GeForce RTX 3060/PCIe/SSE2", False),
    ("AMD Radeon Pro 5500M OpenGL Engine", False), ("Apple M2", False)])
def test_auto_renders_on_the_server_where_opengl_is_software(name, software):
    assert render_mode.is_software(name) is software
    assert render_mode.choose("auto", lambda: name) == ("server" if software else "browser")
    asked = []
    assert render_mode.choose("browser", lambda: asked.append(1) or name) == "browser"
    assert render_mode.choose("server", lambda: asked.append(1) or name) == "server"
    assert asked == []                               # a given mode needs no probe


def test_a_mode_that_does_not_exist_is_refused():
    with pytest.raises(ValueError, match="'gpu'"):
        render_mode.choose("gpu", lambda: "llvmpipe")


def test_this_machine_reports_its_opengl_renderer():
    pytest.importorskip("vtkmodules")
    assert render_mode.server_renderer() != ""
