"""When the studio's check runs (``CheckTimer``), in-process on an event loop: at once after an
edit, with the slider steps arriving meanwhile joined; after a server-rendered slider step,
only once its image has been published and the page draws it, or at the latest
``VIEW_SHOWN_WAIT_S`` after the publication."""
import asyncio
import time

from stitchswitch.studio import check_timer
from stitchswitch.studio.check_timer import CheckTimer


def on_loop(body) -> list:
    """Run the coroutine ``body(timer, ran)`` on an event loop; ``ran`` collects the times the
    timer's check ran."""
    ran: list = []
    asyncio.run(body(CheckTimer(lambda: ran.append(time.perf_counter())), ran))
    return ran


def test_a_check_runs_at_once_and_the_steps_meanwhile_join_it():
    async def body(c, ran):
        c.soon()
        c.soon()
        assert c.pending and ran == []
        await asyncio.sleep(0.05)
        assert not c.pending

    assert len(on_loop(body)) == 1


def test_a_slider_steps_check_waits_for_its_image_then_for_the_page(monkeypatch):
    monkeypatch.setattr(check_timer, "VIEW_SHOWN_WAIT_S", 5.0)

    async def body(c, ran):
        c.after_image()
        c.view_shown()                   # an earlier image drawn: this step's is not out yet
        await asyncio.sleep(0.05)
        assert ran == [] and c.pending
        c.image_published()
        await asyncio.sleep(0.05)
        assert ran == [] and c.pending   # published, not yet drawn
        t0 = time.perf_counter()
        c.view_shown()
        await asyncio.sleep(0.05)
        assert len(ran) == 1 and ran[0] - t0 < 0.04 and not c.pending
        c.view_shown()                   # nothing waits: nothing runs
        await asyncio.sleep(0.02)

    assert len(on_loop(body)) == 1


def test_without_word_from_the_page_the_check_runs_after_the_wait(monkeypatch):
    monkeypatch.setattr(check_timer, "VIEW_SHOWN_WAIT_S", 0.1)
    published = []

    async def body(c, ran):
        c.after_image()
        published.append(time.perf_counter())
        c.image_published()
        await asyncio.sleep(0.05)
        assert ran == []
        await asyncio.sleep(0.15)

    ran = on_loop(body)
    assert len(ran) == 1 and ran[0] - published[0] >= 0.1


def test_a_check_already_due_is_not_brought_forward_by_the_page():
    """A check that another edit made due keeps its own timer: the page's word is only for a
    check that waits for it."""
    async def body(c, ran):
        c.soon(0.1)
        c.after_image()
        c.image_published()              # joins the due check
        c.view_shown()
        await asyncio.sleep(0.05)
        assert ran == []
        await asyncio.sleep(0.1)

    assert len(on_loop(body)) == 1


def test_publication_without_a_waiting_check_schedules_nothing():
    async def body(c, ran):
        c.image_published()
        assert not c.pending
        await asyncio.sleep(0.02)

    assert on_loop(body) == []
