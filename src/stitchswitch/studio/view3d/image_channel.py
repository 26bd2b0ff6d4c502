"""Sending the 3D view as an image rendered on the server (trame-vtk's remote view), for a
browser whose WebGL is a software renderer (``render_mode``).

``VtkRemoteView.update`` renders the render window and hands the frame to vtkWebApplication's
image encoder, which encodes it in a thread of its own: the image the call publishes is the
newest one already encoded, the previous frame's, or none. trame-vtk then asks again after
0.5 s. Here the newest image is asked for again every ``POLL_S`` until the encoder has none
left in progress (vtkWebApplication's ``GetHasImagesBeingProcessed``), so the page gets the
frame of an edit a few milliseconds after it is rendered rather than half a second later.

Rendering happens in the call, so nothing is in flight between edits: ``loaded`` (the local
view's acknowledgement, which ``ViewChannel`` waits for) does nothing here. ``delivered`` is
called once the edit's image has been published (or the polls gave up), so that work which
would hold the event loop (the constraint check after a slider step) can wait until the
image is on its way instead of holding up the polls.
"""
from __future__ import annotations

import asyncio
import time

#: how often the encoder is asked for the edit's image while it is still encoding
POLL_S = 0.003
#: asking stops after this many polls (trame-vtk's own retry, after 0.5 s, remains)
MAX_POLLS = 100


def image_delivery(protocol):
    """trame-vtk's image delivery protocol among the server's link protocols (the object that
    publishes the remote view's images), or None."""
    from trame_vtk.modules.vtk.protocols import vtkWebPublishImageDelivery

    return next((p for p in protocol.getLinkProtocols()
                 if isinstance(p, vtkWebPublishImageDelivery)), None)


class ImageChannel:
    """``server``: the trame server; ``view``: its ``VtkRemoteView`` of ``render_window``;
    ``build``: called before each image to bring the render window up to date,
    ``after_send(send_s, send_cpu_s)`` after it with the time the render and push took;
    ``delivered()`` once the image has been published. ``send()`` renders the current scene
    and pushes its image."""

    def __init__(self, server, view, render_window, build, after_send, delivered=lambda: None):
        self.server = server
        self.view = view
        self.render_window = render_window
        self.build = build
        self.after_send = after_send
        self.delivered = delivered
        self.sent = 0                        # images rendered and pushed
        self.polls = 0                       # extra asks for an image still being encoded
        self._delivery = None
        self._poll = None

    def send(self) -> None:
        """Render the current scene and push its image."""
        self.build()
        if not self.server.protocol:
            self.delivered()
            return
        t0, c0 = time.perf_counter(), time.process_time()
        self.view.update()
        self.sent += 1
        self.after_send(time.perf_counter() - t0, time.process_time() - c0)
        if self._poll is not None:
            self._poll.cancel()
        self._follow(0)

    def _follow(self, n: int) -> None:
        self._poll = None
        if self._delivery is None:
            self._delivery = image_delivery(self.server.protocol)
        if (self._delivery is None or n >= MAX_POLLS
                or not self._delivery.app.GetHasImagesBeingProcessed(self.render_window)):
            self.delivered()
            return
        self._poll = asyncio.get_event_loop().call_later(POLL_S, self._push_newest, n + 1)

    def _push_newest(self, n: int) -> None:
        self.polls += 1
        self._delivery.push_render(str(self._delivery.get_global_id(self.render_window)))
        self._follow(n)

    def loaded(self) -> None:
        """Nothing is in flight between edits (see the module docstring)."""
