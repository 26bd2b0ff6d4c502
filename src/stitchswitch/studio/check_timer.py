"""When the studio's constraint check runs after an edit.

After most edits the check runs at once, on a 1 ms timer, so that slider steps arriving
meanwhile join it and it takes the latest design. After a slider step whose 3D view is
rendered on the server, it waits until the page has the step's image. Run before the image
has been published, the check holds the image back on the server by its own time. Run as
soon as the image has been published, its panel's message arrives while the page is loading
the image and delays the image's drawing (docs/studio.md, "Speed"). So once the image has been
published (``image_published``), the check runs when the page says it is drawing the image
(``view_shown``), and at the latest ``VIEW_SHOWN_WAIT_S`` later: a hidden tab draws no
frames and sends no such word.
"""
from __future__ import annotations

import asyncio

#: the delay of a check that runs at once (slider steps arriving meanwhile join it)
SOON_S = 0.001
#: a check waiting for the page to draw a slider step's image runs at the latest this long
#: after the image was published
VIEW_SHOWN_WAIT_S = 0.25


class CheckTimer:
    """Schedules ``run`` (the check and its panel) on the running event loop."""

    def __init__(self, run):
        self.run = run
        self._timer = None
        self._after_image = False     # a slider step's check waits for its image's publication
        self._waits_view = False      # ... and then for the page's word that it draws it

    @property
    def pending(self) -> bool:
        return self._timer is not None or self._after_image

    def soon(self, delay_s: float = SOON_S) -> None:
        """Run the check after ``delay_s``, unless one is already due (it takes the latest
        design)."""
        if self._timer is None:
            self._timer = asyncio.get_event_loop().call_later(delay_s, self._fire)

    def after_image(self) -> None:
        """The check of this edit waits until its image has been published and drawn."""
        self._after_image = True

    def image_published(self) -> None:
        """The 3D view's image has gone out: a check waiting for it now waits for the page."""
        if self._after_image:
            self._after_image = False
            self._waits_view = self._timer is None
            self.soon(VIEW_SHOWN_WAIT_S)

    def view_shown(self) -> None:
        """The page is drawing an image of the view: a check waiting for that runs."""
        if self._waits_view and self._timer is not None:
            self._timer.cancel()
            self._timer = None
            self._waits_view = False
            self.soon()

    def _fire(self) -> None:
        self._timer = None
        self._waits_view = False
        self.run()
