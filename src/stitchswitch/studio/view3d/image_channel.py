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

A dragged slider's images are drafts (``send(draft=True)``): rendered at ``DRAFT_RATIO`` of the
view's width and height, a quarter of its pixels, and stretched to the view by the page, as
trame-vtk's ``interactive_ratio`` does while the user rotates. On two cores shared with the
browser, the full-size frame of the 40-patch benchmark design took 20-28 ms to render and
capture and its 38 kB were decoded and composited beside it; the draft takes 11-15 ms and
17 kB, and the slider step's image is painted a little sooner (docs/studio.md, "Speed"). Once the
edits pause for ``STILL_AFTER_S`` the view is rendered again at full size and still quality;
any other image (a moved patch, a new check's outlines) is full size at once.
"""
from __future__ import annotations

import asyncio
import time

#: how often the encoder is asked for the edit's image while it is still encoding
POLL_S = 0.003
#: asking stops after this many polls (trame-vtk's own retry, after 0.5 s, remains)
MAX_POLLS = 100
#: a draft image's share of the view's width and height
DRAFT_RATIO = 0.5
#: the full-size image follows the last draft after this pause
STILL_AFTER_S = 0.3


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
    ``delivered()`` once the image has been published; ``still_quality`` and
    ``draft_quality``: the JPEG qualities of full-size and draft images. ``send()`` renders the
    current scene and pushes its image."""

    def __init__(self, server, view, render_window, build, after_send, delivered=lambda: None,
                 still_quality: int = 90, draft_quality: int = 70):
        self.server = server
        self.view = view
        self.render_window = render_window
        self.build = build
        self.after_send = after_send
        self.delivered = delivered
        self.quality = {False: still_quality, True: draft_quality}
        self.sent = 0                        # images rendered and pushed
        self.drafts = 0                      # ... of which drafts
        self.polls = 0                       # extra asks for an image still being encoded
        self._delivery = None
        self._poll = None
        self._still = None                   # the full-size image due after the drafts
        self._owes_delivered = False         # an edit's image is not yet known published
        self._times = (0.0, 0.0)             # the last render's wall and CPU time

    def send(self, draft: bool = False) -> None:
        """Render the current scene and push its image; a ``draft`` at ``DRAFT_RATIO`` of the
        view's size, followed by the full-size image once no other ``send`` has come for
        ``STILL_AFTER_S``."""
        self.build()
        if not self.server.protocol:
            self.delivered()
            return
        self._render(draft)
        self.after_send(*self._times)
        self._owes_delivered = True
        self._follow(0)

    def _render(self, draft: bool) -> None:
        if self._still is not None:
            self._still.cancel()
            self._still = None
        self._size_for(draft)
        t0, c0 = time.perf_counter(), time.process_time()
        self.view.update()
        self._times = (time.perf_counter() - t0, time.process_time() - c0)
        self.sent += 1
        if self._poll is not None:
            self._poll.cancel()
            self._poll = None
        if draft:
            self.drafts += 1
            self._still = asyncio.get_event_loop().call_later(STILL_AFTER_S, self._send_still)

    def _send_still(self) -> None:
        """The full-size image of the scene the last draft showed (nothing has changed since:
        a change would have sent its own image): no build, and not an edit's image for
        ``after_send``."""
        self._still = None
        if self.server.protocol:
            self._render(False)
            self._follow(0)

    def _size_for(self, draft: bool) -> None:
        """The image delivery's ratio and quality for the next image (trame-vtk's own
        ``viewport.image.push.quality``, which resizes the render window): a no-op until the
        view's first image has given the delivery the view's size."""
        delivery = self._image_delivery()
        if delivery is None:
            return
        view_id = str(delivery.get_global_id(self.render_window))
        ratio = DRAFT_RATIO if draft else 1.0
        tracked = delivery.tracking_views.get(view_id)
        if tracked is not None and (tracked.get("ratio", 1.0), tracked.get("quality")) != (
                ratio, self.quality[draft]):
            delivery.set_view_quality(view_id, self.quality[draft], ratio)

    def _image_delivery(self):
        if self._delivery is None:
            self._delivery = image_delivery(self.server.protocol)
        return self._delivery

    def _follow(self, n: int) -> None:
        self._poll = None
        delivery = self._image_delivery()
        if (delivery is None or n >= MAX_POLLS
                or not delivery.app.GetHasImagesBeingProcessed(self.render_window)):
            if self._owes_delivered:
                self._owes_delivered = False
                self.delivered()
            return
        self._poll = asyncio.get_event_loop().call_later(POLL_S, self._push_newest, n + 1)

    def _push_newest(self, n: int) -> None:
        self.polls += 1
        self._delivery.push_render(str(self._delivery.get_global_id(self.render_window)))
        self._follow(n)

    def loaded(self) -> None:
        """Nothing is in flight between edits (see the module docstring)."""
