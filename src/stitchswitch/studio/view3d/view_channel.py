"""Sending the 3D view's scene to the page: on each edit only the change (trame-vtk's delta:
the scene description with the new arrays' checksums), at most one scene in flight (the newest
wins), and the whole scene state, which a page opened later starts from, once edits pause.

trame-vtk's ``VtkLocalView.update`` serializes the whole view twice on every call: the delta
for the open pages and the full state, which is stored in the shared state and so also sent to
every open page, which ignores it. Per edit only the delta is needed; the full state can wait
until the edits stop (``FULL_STATE_DELAY_S``): a page opened meanwhile shows the scene of the
last pause until then.

In flight: a scene sent and not yet acknowledged by a page (``loaded``, which the page calls
when vtk.js has loaded it). A scene asked for meanwhile waits, and only the newest is sent on
the acknowledgement, so a dragged slider never queues scenes behind the browser; without an
acknowledgement (no page open) the wait ends after ``IN_FLIGHT_TIMEOUT_S``.
"""
from __future__ import annotations

import asyncio
import time

FULL_STATE_DELAY_S = 1.0
IN_FLIGHT_TIMEOUT_S = 1.0


class ViewChannel:
    """``server``: the trame server; ``view``: its ``VtkLocalView`` of ``render_window``, made
    with ``ref=ref``; ``build``: called before each send to bring the render window up to date,
    ``after_send(send_s, send_cpu_s)`` after it with the time the delta took. ``send()`` asks
    for a scene; ``loaded()`` is the page's acknowledgement."""

    def __init__(self, server, view, render_window, ref: str, build, after_send):
        self.server = server
        self.view = view
        self.render_window = render_window
        self.scene_key = f"scene_{ref}"      # the state key VtkLocalView reads the full state from
        self.build = build
        self.after_send = after_send
        self.in_flight = False
        self.waiting = False
        self.sent = 0                        # scenes sent (deltas published)
        self._timeout = None
        self._full = None

    def send(self) -> None:
        """Send the current scene now, or when the scene in flight has been loaded."""
        if self.in_flight:
            self.waiting = True
            return
        self.waiting = False
        self.build()
        if not self.server.protocol:
            return
        t0, c0 = time.perf_counter(), time.process_time()
        # the delta half of VtkLocalView.update (the widget's own module helper)
        delta = self.view._helper.scene(self.render_window, new_state=False)
        self.server.protocol.publish("trame.vtk.delta", delta)
        self.sent += 1
        self.after_send(time.perf_counter() - t0, time.process_time() - c0)
        self.in_flight = True
        loop = asyncio.get_event_loop()
        if self._timeout is not None:
            self._timeout.cancel()
        self._timeout = loop.call_later(IN_FLIGHT_TIMEOUT_S, self.loaded)
        if self._full is not None:
            self._full.cancel()
        self._full = loop.call_later(FULL_STATE_DELAY_S, self.store_full_state)

    def loaded(self) -> None:
        """A page has loaded the scene in flight: send the newest one if another was asked for."""
        if self._timeout is not None:
            self._timeout.cancel()
            self._timeout = None
        self.in_flight = False
        if self.waiting:
            self.send()

    def store_full_state(self) -> None:
        """The whole scene state, for pages opened later (the full half of ``update``)."""
        self._full = None
        if self.server.protocol:
            self.server.state[self.scene_key] = self.view._helper.scene(self.render_window,
                                                                        new_state=True)
            self.server.state.flush()          # now, not with the next edit's messages
