"""The 3D view's channel in-process (fake server and view): one scene in flight, the newest
sent on the page's acknowledgement, the full scene state stored once the edits pause."""
import asyncio

from stitchswitch.studio.view3d import view_channel
from stitchswitch.studio.view3d.view_channel import ViewChannel


class FakeState(dict):
    def __init__(self):
        super().__init__()
        self.flushes = 0

    def flush(self):
        self.flushes += 1


class FakeProtocol:
    def __init__(self):
        self.published = []

    def publish(self, topic, message):
        self.published.append((topic, message))


class FakeServer:
    def __init__(self):
        self.protocol, self.state = FakeProtocol(), FakeState()


class FakeHelper:
    def __init__(self, scene):
        self.scene_of = scene

    def scene(self, render_window, new_state=False):
        return {"scene": self.scene_of["n"], "full": new_state}


class FakeView:
    def __init__(self, scene):
        self._helper = FakeHelper(scene)


def test_one_scene_in_flight_newest_wins_full_state_after_a_pause(monkeypatch):
    monkeypatch.setattr(view_channel, "FULL_STATE_DELAY_S", 0.05)
    monkeypatch.setattr(view_channel, "IN_FLIGHT_TIMEOUT_S", 0.2)
    scene = {"n": 0}
    built, sent = [], []

    def build():
        scene["n"] += 1
        built.append(scene["n"])

    async def run():
        server = FakeServer()
        ch = ViewChannel(server, FakeView(scene), "rw", "v", build, lambda *t: sent.append(t))
        ch.send()                                   # scene 1 goes out
        ch.send()                                   # in flight: waits
        ch.send()                                   # still one waiting (the newest is built later)
        assert [m["scene"] for _, m in server.protocol.published] == [1] and built == [1]
        assert "scene_v" not in server.state
        ch.loaded()                                 # the page has scene 1: scene 2 (newest) goes
        assert [m["scene"] for _, m in server.protocol.published] == [1, 2]
        assert all(t == "trame.vtk.delta" and not m["full"] for t, m in server.protocol.published)
        ch.loaded()
        ch.loaded()                                 # nothing waiting: nothing sent
        assert len(server.protocol.published) == 2 and len(sent) == 2
        await asyncio.sleep(0.1)                    # the pause: the full state for new pages
        assert server.state["scene_v"] == {"scene": 2, "full": True} and server.state.flushes == 1
        ch.send()                                   # scene 3; no acknowledgement comes
        ch.send()
        await asyncio.sleep(0.3)                    # the in-flight wait times out: the newest goes
        assert [m["scene"] for _, m in server.protocol.published] == [1, 2, 3, 4]

    asyncio.run(run())
