"""The main screen: parameters, plot tabs, summary, messages and keys.

One rule keeps the screen honest (``MainScreen._reconcile``, run after every
change: a key in an input, enter, leaving an input, a tab, a pin, an
overlay, a scene): the screen tracks the request whose result it shows (per
tab, ``results``) and the one in flight; whenever the complete, valid inputs
shown differ from both (and from a request whose error is shown), they are
solved. While the summary shows the result of other inputs (a value being
typed, an invalid one, a solve waiting or running, an error), the status
line names them with the values the result is for ("showing the result for
V* 0.2"), never "ready". Enter solves what is shown unless the screen shows
it. The gauge (V*_cr, V*_R) follows the inputs shown: it needs no solve.

Every computation runs in one exclusive thread worker; each request carries
a generation number and a result (or error) from an older generation is
dropped, so a stale result never overwrites a newer one. Each worker has its
own cancellation token (``movingpunch.Cancel``), bound to its thread: a newer
request, a shown result that makes it moot, or quitting cancels it and the
solve stops within about 50 ms (it vanishes silently: nothing of it is
shown), so an abandoned near-critical solve does not go on burning a core
while the next one waits. Escape outside the inputs cancels the computation
in flight on the user's request: the status says "cancelled" (with the
values the screen shows instead) and the inputs are not solved again until
they change, ``r`` or enter.

Typing is debounced: a valid value is solved once the user pauses for
``DEBOUNCE_SECONDS`` (or presses enter), and a value still being typed
(``0.``, ``1e``, ``-``, an empty box) is neither solved nor refused. So a
half-typed value never replaces the result on screen, and after an error the
screen keeps the last result the user saw.
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import replace
from typing import ClassVar

from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical
from textual.screen import Screen
from textual.timer import Timer
from textual.widgets import (
    Footer,
    Input,
    ProgressBar,
    Static,
    TabbedContent,
    TabPane,
    Tabs,
)
from textual.worker import Worker, WorkerState, get_current_worker

from movingpunch._display import drag_scale, shown
from movingpunch.cancel import Cancel
from movingpunch.errors import (
    Cancelled,
    ConvergenceError,
    InvalidParameterError,
    MovingPunchError,
    SupercriticalSpeedError,
    UnphysicalContactError,
)
from movingpunch.outputs import atomic_write
from movingpunch.params import PRESETS
from movingpunch.scene import Scene
from movingpunch.tui import model, scene_files
from movingpunch.tui.messages import Computed, Progressed
from movingpunch.tui.model import (
    TABS,
    AccuracyTable,
    Cache,
    FieldMap,
    FieldQuantity,
    Notice,
    Overlay,
    Params,
    Request,
    Result,
    SweepSpec,
    TabName,
    fmt,
    format_punches,
)
from movingpunch.tui.paths import WorkingFolder, write_error
from movingpunch.tui.screens.help import HelpScreen, MessagesScreen
from movingpunch.tui.screens.medium import MediumChoice, MediumEditor
from movingpunch.tui.screens.prompts import OverlayPrompt, PathPrompt
from movingpunch.tui.widgets import (
    AccuracyView,
    CurvePlot,
    Gauge,
    ParamsPanel,
    StressMap,
)
from movingpunch.tui.widgets.fields import Field, FieldsLine
from movingpunch.tui.widgets.params import (
    FULL_TEXT_KEY,
    INPUTS,
    LABELS,
    STATUS_LINES,
    MessageLine,
    applies,
)
from movingpunch.zones import CONTACT_MODES

DEBOUNCE_SECONDS = 0.2
"""A typed value is solved after the user pauses this long (or on enter)."""

NARROW_TABS = 54
"""Below this many columns for the tab bar, the tabs take their short names."""

TAB_TITLES: dict[TabName, str] = {
    "pressure": "p(x)",
    "surface": "σx(x,0)",
    "depth": "σx(0,y)",
    "sweep": "a/h sweep",
    "field": "field",
    "accuracy": "accuracy",
}

SHORT_TAB_TITLES: dict[TabName, str] = {
    "pressure": "p(x)",
    "surface": "σx(x)",
    "depth": "σx(y)",
    "sweep": "sweep",
    "field": "field",
    "accuracy": "accuracy",
}
"""The tabs' names on a narrow terminal (80 columns): whole words, never cut."""

FIGURE_TABS: dict[str, TabName] = {
    "fig2": "sweep",
    "fig3": "sweep",
    "fig4": "pressure",
    "fig5": "pressure",
    "fig6": "pressure",
}


class MainScreen(Screen[None]):
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("r", "recompute", "Recompute"),
        Binding("p", "pin", "Pin"),
        Binding("c", "clear_pins", "Clear"),
        Binding("right_square_bracket", "next_tab", "Tab", key_display="]"),
        Binding(
            "left_square_bracket",
            "previous_tab",
            "Previous tab",
            key_display="[",
            show=False,
        ),
        Binding("v", "overlay", "Vary"),
        Binding("l", "medium", "Medium", show=False),
        Binding("o", "open_scene", "Open"),
        Binding("s", "save_scene", "Save"),
        Binding("e", "export", "CSV"),
        Binding("question_mark,f1", "help", "Help", key_display="?"),
        Binding(FULL_TEXT_KEY, "messages", "All"),  # shown while one is shortened
        Binding(FULL_TEXT_KEY, "all_messages", "All", show=False),
        Binding("q", "quit", "Quit"),
        # Priority: the app handles these as it takes each key from the
        # terminal, before it hands the next key on; a key handed to the
        # focused input would reach the screen's bindings only after the
        # keys typed behind it had gone where the focus was (Escape then
        # ``i07e`` fast on a busy machine: ``i07e`` went to the old input,
        # or ``e`` to Export).
        Binding(
            "escape", "leave_input", "Leave input", key_display="esc", priority=True
        ),
        Binding("escape", "cancel", "Cancel", key_display="esc"),
        Binding("i", "edit", "Edit the inputs", show=False, priority=True),
        Binding("m", "toggle_quantity", "σx/VM", show=False),
        Binding("w", "toggle_sweep", "Sweep R/P/V*", show=False),
        *(
            Binding(str(i + 1), f"show_tab('{tab}')", TAB_TITLES[tab], show=False)
            for i, tab in enumerate(TABS)
        ),
        *(
            Binding(f"f{n}", f"figure('fig{n}')", f"Fig. {n}", show=False)
            for n in range(2, 7)
        ),
    ]

    def __init__(
        self,
        params: Params,
        *,
        overlay: Overlay | None = None,
        sweep: SweepSpec | None = None,
        show_timing: bool = True,
        cursor_blink: bool = True,
        tab: TabName = "pressure",
        folder: WorkingFolder | None = None,
    ) -> None:
        super().__init__()
        self.folder = folder or WorkingFolder.at()
        """Where Open, Save and Export read and write (paths stay inside)."""
        self.params = params
        """The inputs shown, each at its last complete, valid value (the
        result on screen may be of another set: ``result.request.params``)."""
        self.overlay = overlay
        self.sweep = sweep or SweepSpec()
        self.pins: list[Params] = []
        self.quantity: FieldQuantity = "sigma_x"
        self.cache = Cache()
        self.generation = 0
        self.result: Result | None = None
        """The newest result shown (its request's params and tab)."""
        self.results: dict[TabName, Result] = {}
        self.redraw_seconds: list[float] = []
        """Time from a parameter change to its summary on screen."""
        self._changed_at: dict[int, float] = {}
        self._worker_generation: dict[Worker[None], int] = {}
        self._show_timing = show_timing
        self._cursor_blink = cursor_blink
        self._initial_tab = tab
        self._invalid: set[str] = set()
        self._status_error = ""
        self._notes: tuple[str, ...] = ()
        self._warnings: tuple[str, ...] = ()
        self._hints: tuple[str, ...] = ()
        self._typing: set[str] = set()
        """Inputs holding a value still being typed (``0.``, ``1e``, empty)."""
        self._editing = ""
        """The input the user edited last (an error that concerns it goes there)."""
        self._solve_timer: Timer | None = None
        self.debounce = DEBOUNCE_SECONDS
        """Seconds of pause after a key before a typed value is solved."""
        self._status_shown: Text | None = None
        """The status line's text (updated only when it changes: an update
        lays the screen out again)."""
        self._in_flight: Request | None = None
        """What the running worker computes (generation 0), if anything."""
        self._failed: tuple[Request, BaseException | None] | None = None
        """The request whose error is on screen, and its error."""
        self._limits: dict[tuple[object, ...], tuple[float, float] | None] = {}
        """(V*_cr, V*_R) per (kw, ν, kp, sublayers, half-space): the gauge's
        speeds (None: the medium's refused)."""
        self.requested: list[Params] = []
        """Every parameter set sent to a worker, oldest first, a repeat of
        the one before (another tab, a pin) not counted (for tests)."""
        self._last_file = "scene.toml"
        """What Open and Save suggest: the last scene file saved or opened."""
        self._tokens: dict[int, Cancel] = {}
        """The cancellation token of each computation started and not yet
        cancelled, by generation (cancelled when superseded)."""
        self._cancelled: Request | None = None
        """The request the user cancelled (escape): not solved again until
        the inputs change, ``r`` or enter."""
        self._computing_lock = threading.Lock()
        self._computing: set[int] = set()
        """Generations whose worker thread is still computing (a cancelled
        one leaves within about 50 ms; for tests and quitting)."""

    # -- layout -------------------------------------------------------------

    def compose(self) -> ComposeResult:
        with Horizontal(id="body"):
            yield ParamsPanel(self.params, cursor_blink=self._cursor_blink)
            with TabbedContent(id="tabs", initial=f"tab-{self._initial_tab}"):
                for tab in TABS:
                    with TabPane(TAB_TITLES[tab], id=f"tab-{tab}"):
                        if tab == "field":
                            yield StressMap(id="plot-field")
                        elif tab == "accuracy":
                            yield AccuracyView(id="plot-accuracy")
                        else:
                            yield CurvePlot(id=f"plot-{tab}")
        with Vertical(id="bottom"):
            yield FieldsLine(id="summary")
            with Horizontal(id="status-row"):
                yield MessageLine(title="status", lines=STATUS_LINES, id="status")
                yield ProgressBar(id="progress", show_eta=False)
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.query_one("#tabs", TabbedContent).query_one(Tabs).focus()
        self._fit_tab_titles()
        self.request()

    def on_resize(self) -> None:
        self._fit_tab_titles()

    def _fit_tab_titles(self) -> None:
        """Long tab names where they fit, short ones (whole words) where not."""
        tabs = self.query_one("#tabs", TabbedContent)
        width = tabs.size.width or (self.size.width - 30)
        titles = TAB_TITLES if width >= NARROW_TABS else SHORT_TAB_TITLES
        for tab in TABS:
            pane = tabs.get_tab(f"tab-{tab}")
            if str(pane.label) != titles[tab]:
                pane.label = titles[tab]

    # -- state --------------------------------------------------------------

    @property
    def tab(self) -> TabName:
        active = self.query_one("#tabs", TabbedContent).active
        name = active.removeprefix("tab-")
        assert name in TABS
        return name

    @property
    def solve_pending(self) -> bool:
        """A typed value waits for the user's pause before it is solved."""
        return self._solve_timer is not None

    def wanted(self) -> Request | None:
        """What the screen must show now (generation 0): the visible tab for
        the inputs shown, the pins, the overlay; None while an input holds a
        value being typed or an invalid one (nothing complete to solve)."""
        if self._invalid or self._typing:
            return None
        return Request(
            generation=0,
            params=self.params,
            tab=self.tab,
            pins=tuple(self.pins),
            overlay=self.overlay,
            sweep=self.sweep,
            quantity=self.quantity,
        )

    def _reconcile(self, *, soon: bool) -> None:
        """The one rule of the screen's state, run after every change: when
        the complete, valid inputs shown differ from what the screen shows
        and nothing in flight (or an error shown for them) covers them, they
        are solved, after the user's pause when ``soon`` (typing), else now
        (enter, leaving an input, a tab, a pin, a scene). What the screen
        shows is tracked, never inferred from what changed last."""
        wanted = self.wanted()
        if wanted is None or self._covered(wanted):
            self._stop_timer()
        elif soon:
            self._stop_timer()
            self._solve_timer = self.set_timer(self.debounce, self._paused)
        else:
            self._stop_timer()
            self._start(wanted)
        self._update_status()

    def _paused(self) -> None:
        self._solve_timer = None
        self._reconcile(soon=False)

    def _stop_timer(self) -> None:
        if self._solve_timer is not None:
            self._solve_timer.stop()
            self._solve_timer = None

    def _covered(self, wanted: Request) -> bool:
        """Whether ``wanted`` is on screen, in flight, or its error is shown.
        A tab's own earlier result for ``wanted`` is shown again; a request in
        flight for something else is then dropped (its result would replace
        the right one)."""
        if self._in_flight == wanted:
            return True
        if self._failed is not None and self._failed[0] == wanted:
            if self._in_flight is not None:
                self._drop_in_flight()
            self.show_error(self._failed[1], wanted.params)  # its message again
            return True
        shown = self.results.get(wanted.tab)
        if shown is None or _key(shown.request) != wanted:
            # The user cancelled it: solved again on r, enter or a change.
            return self._cancelled == wanted
        if self._in_flight is not None:
            self._drop_in_flight()
        if self.result is not shown or self._failed or self._status_error:
            self._display(shown)  # (an error of another set goes)
        return True

    def _drop_in_flight(self) -> None:
        """A newer generation: the running worker's token is cancelled (its
        solve stops within about 50 ms) and its result, if any, is dropped."""
        self._cancel_all()
        self.generation += 1
        self._in_flight = None
        self.query_one("#progress", ProgressBar).remove_class("-busy")

    def request(self) -> None:
        """Computes what the visible tab needs for the current state, even if
        the screen shows it (``r``, the first solve); nothing while an input
        is being typed into or is invalid."""
        self._stop_timer()
        wanted = self.wanted()
        if wanted is not None:
            self._start(wanted)
        self._update_status()

    def _cancel_all(self) -> None:
        """Cancels every computation started (a superseded one vanishes:
        its worker drops what it computed)."""
        for token in self._tokens.values():
            token.cancel()
        self._tokens.clear()

    @property
    def computations_running(self) -> int:
        """Worker threads still computing, cancelled ones included."""
        with self._computing_lock:
            return len(self._computing)

    def _start(self, wanted: Request) -> None:
        self._cancel_all()  # superseded: the older computation stops
        self._cancelled = None
        self.generation += 1
        self._in_flight = wanted
        self._failed = None  # an error shown is of an older request now
        self._status_error = ""
        if not self.requested or self.requested[-1] != wanted.params:
            self.requested.append(wanted.params)
        request = replace(wanted, generation=self.generation)
        self._changed_at[self.generation] = time.perf_counter()
        bar = self.query_one("#progress", ProgressBar)
        bar.update(total=None, progress=0)
        bar.add_class("-busy")
        token = Cancel()
        self._tokens[request.generation] = token
        worker = self._compute(request, token)
        self._worker_generation[worker] = request.generation
        self.refresh_bindings()  # escape cancels (outside the inputs)

    @work(thread=True, exclusive=True, exit_on_error=False, group="compute")
    def _compute(self, request: Request, token: Cancel) -> None:
        worker = get_current_worker()
        generation = request.generation

        def progress(done: int, total: int) -> None:
            self.post_message(Progressed(generation, done, total))

        def cancelled() -> bool:
            return (
                token.cancelled or worker.is_cancelled or self.generation != generation
            )

        with self._computing_lock:
            self._computing.add(generation)
        try:
            with token:  # every call of the core on this thread checks it
                result = model.compute(self.cache, request, progress, cancelled)
        except Cancelled:
            return  # superseded, escape or quit: nothing of it is shown
        finally:
            with self._computing_lock:
                self._computing.discard(generation)
        if result is not None:
            self.post_message(Computed(result))

    # -- results ------------------------------------------------------------

    def on_progressed(self, message: Progressed) -> None:
        if message.generation == self.generation:
            bar = self.query_one("#progress", ProgressBar)
            bar.update(total=message.total, progress=message.done)

    def on_computed(self, message: Computed) -> None:
        result = message.result
        generation = result.request.generation
        if generation != self.generation:
            return  # stale: a newer request is running or done
        started = self._changed_at.pop(generation, None)
        self._in_flight = None
        self._tokens.pop(generation, None)
        self._display(result)
        self.refresh_bindings()
        if started is not None:
            self.redraw_seconds.append(time.perf_counter() - started)

    def _display(self, result: Result) -> None:
        """Puts ``result`` on screen: the summary, its tab's plot, the status."""
        self.result = result
        self.results[result.request.tab] = result
        self._failed = None
        self._status_error = ""
        self._notes = result.notes
        self._warnings = result.summary.warnings
        self._hints = model.summary_hints(result.summary)
        self._clear_solver_messages()
        self._show(result)
        self.query_one("#progress", ProgressBar).remove_class("-busy")

    def _sync_plot(self) -> None:
        """The visible tab's plot shows the set the summary shows, or
        nothing: a tab's earlier result for other inputs is not left beside
        the summary (its result stays in ``results``, shown again when the
        inputs come back to it)."""
        tab = self.tab
        result = self.results.get(tab)
        summary = self.result
        if (
            result is not None
            and summary is not None
            and result.request.params == summary.request.params
        ):
            return
        text = (
            "computing..."
            if self._in_flight is not None
            else "no result for the inputs shown: see the status line"
        )
        widget = self.query_one(f"#plot-{tab}")
        if isinstance(widget, CurvePlot):
            widget.curves = None
            widget.placeholder = text
        elif isinstance(widget, StressMap):
            widget.field = None
            widget.placeholder = text
        elif isinstance(widget, AccuracyView):
            widget.table = None
            widget.placeholder = text

    def on_worker_state_changed(self, event: Worker.StateChanged) -> None:
        worker = event.worker
        if event.state not in (
            WorkerState.ERROR,
            WorkerState.SUCCESS,
            WorkerState.CANCELLED,
        ):
            return
        generation = self._worker_generation.pop(worker, None)
        if generation != self.generation or self._in_flight is None:
            return
        failed = self._in_flight
        self._in_flight = None
        self.refresh_bindings()
        self.query_one("#progress", ProgressBar).remove_class("-busy")
        if event.state == WorkerState.ERROR:
            self._failed = (failed, worker.error)
            self.show_error(worker.error, failed.params)
            self._sync_plot()
        else:  # ended without a result (cancelled)
            self._update_status()

    def show_error(
        self, error: BaseException | None, params: Params | None = None
    ) -> None:
        """An error of the solve of ``params`` (default: the inputs shown),
        inline; the last result stays, and the status says for which inputs."""
        params = params or self.params
        self._clear_solver_messages()
        if isinstance(error, SupercriticalSpeedError):
            vcr = error.critical_vstar
            vr = error.rayleigh_vstar
            if vcr is not None and vr is not None:
                self.query_one(Gauge).damped = False
                self.query_one(Gauge).limits = (params.vstar, vcr, vr)
                kp = params.kp
                self._set_message(
                    "vstar",
                    f"V* = {fmt(params.vstar, 5)} is at or above V*_cr = "
                    f"{fmt(vcr, 6)} (kw {fmt(params.kw, 4)}, ν "
                    f"{fmt(params.nu, 4)}{f', kp {fmt(kp, 4)}' if kp else ''}): "
                    "need 0 <= V* < V*_cr",
                )
            else:
                self._set_message("vstar", _one_line(error))
            self._status_error = "supercritical speed: no steady solution"
        elif isinstance(error, InvalidParameterError):
            name = self._field_of(error)
            if name:
                self._set_message(name, _one_line(error))
            self._status_error = (
                f"{LABELS[name]}: {_one_line(error)}" if name else _one_line(error)
            )
        elif isinstance(error, UnphysicalContactError):
            self._status_error = "unphysical contact: " + _one_line(error)
            if params.contact == "single" and not params.punches:
                # its own item (two spaces): a summary of the error keeps it
                self._status_error += "  (contact auto finds the contact zones)"
        elif isinstance(error, ConvergenceError):
            self._status_error = "no convergence: " + _one_line(error)
        else:
            what = type(error).__name__ if error is not None else "error"
            self._status_error = f"{what}: {_one_line(error)}"
        self._update_status()

    def _field_of(self, error: InvalidParameterError) -> str:
        """The input an error belongs under: the one being edited when the
        error concerns it (``radius * load = ...`` while editing P/(μh) goes
        under P/(μh)), else the error's own parameter; "" for none."""
        name = error.parameter or ""
        if name == "at":  # a punch's position: the train's input
            name = "punches"
        words = set(str(error).replace("=", " ").replace(",", " ").split())
        editing = self._editing
        if editing and (editing == name or editing in words):
            return editing
        return name if name in INPUTS else ""

    def _clear_solver_messages(self) -> None:
        """Messages from the solver (not from typing) go when a solve succeeds."""
        panel = self.query_one(ParamsPanel)
        for name in INPUTS:
            if name not in self._invalid and panel.message(name):
                self._set_message(name, "")

    def _show(self, result: Result) -> None:
        self._show_gauge()
        self.query_one("#summary", FieldsLine).fields = self._summary_fields(result)
        data = result.data
        if isinstance(data, Notice):
            widget = self.query_one(f"#plot-{data.tab}")
            if isinstance(widget, AccuracyView):
                widget.table = None
                widget.placeholder = data.text
            elif isinstance(widget, CurvePlot):
                widget.curves = None
                widget.placeholder = data.text
        elif isinstance(data, AccuracyTable):
            view = self.query_one("#plot-accuracy", AccuracyView)
            view.placeholder = "computing the accuracy ladder..."
            view.table = data
        elif isinstance(data, FieldMap):
            self.query_one("#plot-field", StressMap).field = data
        else:
            plot = self.query_one(f"#plot-{data.tab}", CurvePlot)
            plot.placeholder = "computing..."
            plot.curves = data
        self._update_status()

    def _summary_fields(self, result: Result) -> tuple[Field, ...]:
        """The summary's fields for every solution: the contact (a/h, or its
        ends when asymmetric), p0, δ/h, the σx peaks, the drag where there is
        one; packed into lines without breaking a field (``FieldsLine``)."""
        s = result.summary
        start, end = s.contact_interval
        if s.punches:
            parts = _train_parts(s)
        elif len(s.contact_zones) > 1:
            # a separated contact: its zones' ends, x/h
            parts = [(f"{len(s.contact_zones)} zones", _zones_text(s.contact_zones, 4))]
            parts += [("p0", fmt(s.p0, 4)), ("δ/h", fmt(s.indentation, 3))]
        else:
            contact = (
                ("a/h", fmt(s.a, 6))
                if start == -end
                else ("(-b,a)/h", f"({fmt(start, 5)}, {fmt(end, 5)})")
            )
            parts = [
                contact,
                ("p0", fmt(s.p0, 4)),
                ("δ/h", fmt(s.indentation, 3)),
            ]
        parts += [
            ("σx⁺ top", fmt(s.top_tensile, 3)),
            ("bot", fmt(s.bottom_tensile, 3)),
        ]
        if s.damped or abs(s.drag) > 1e-9:  # (a sum of zones' rounding: not shown)
            scale = drag_scale(s.contact_interval, s.params.radius)
            parts.append(("drag/P", fmt(shown(s.drag, scale=scale), 4)))
        if s.end_coefficient != 0.0 and s.end_coefficient_back != s.end_coefficient:
            # a flat punch on the asymmetric solver: both edges
            parts.append(("K back", fmt(s.end_coefficient_back, 4)))
            parts.append(("K front", fmt(s.end_coefficient, 4)))
        elif s.end_coefficient != 0.0:  # a flat punch: singular ends
            parts.append(("K", fmt(s.end_coefficient, 4)))
        if s.tangential_force != 0.0:
            parts.append(("friction/P", fmt(s.tangential_force, 4)))
        parts += [("it", str(s.iterations)), ("err", f"{s.error_estimate:.0e}")]
        if self._show_timing:
            parts.append(("", f"{s.elapsed * 1e3:.1f} ms"))
        fields = [Field(label, value) for label, value in parts]
        if not s.valid:
            fields.append(Field("", "INVALID", "bold red"))
        return tuple(fields)

    def _show_gauge(self) -> None:
        """The gauge of V* against V*_cr and V*_R for the inputs shown (a
        function of kw, ν and kp: no solve), unless an input is unfinished."""
        if self._invalid or self._typing:
            return
        p = self.params
        key = (p.kw, p.nu, p.kp, p.layers, p.half_space)
        if key not in self._limits:
            try:
                self._limits[key] = model.medium_limits(p)
            except MovingPunchError:
                # (a medium the core refuses: the solve's error says why)
                self._limits[key] = None
        speeds = self._limits[key]
        gauge = self.query_one(Gauge)
        if speeds is None:
            gauge.limits = None
            return
        vcr, vr = speeds
        medium = p.medium()
        # Dashpots, or a viscoelastic layer with its inertia: bounded by V*_R.
        gauge.damped = p.damped or (medium is not None and medium.beyond_critical)
        gauge.limits = (p.vstar, vcr, vr)

    def stale_inputs(self) -> tuple[str, ...]:
        """The inputs whose text differs from the set the summary shows, each
        as ``V* 0.2``: its label and the value the summary was computed for
        (an input that does not apply to either set is left out: the shape
        that hides it differs)."""
        if self.result is None:
            return ()
        shown = self.result.request.params
        panel = self.query_one(ParamsPanel)
        out = []
        for name in INPUTS:
            if not (applies(name, shown) and applies(name, self.params)):
                continue
            if _value(shown, name) != self._typed_value(name, panel.text(name)):
                out.append(f"{LABELS[name]} {_input_text(shown, name)}")
        if (shown.layers, shown.half_space) != (
            self.params.layers,
            self.params.half_space,
        ):
            out.append(f"medium {shown.medium_label() or 'homogeneous layer'}")
        return tuple(out)

    def _typed_value(self, name: str, text: str) -> object:
        """The value ``text`` in the input ``name`` stands for (None if it
        stands for none)."""
        try:
            return _value(self._parsed(name, text), name)
        except InvalidParameterError:
            return None

    def _update_status(self) -> None:
        """Says what the screen shows. While the summary shows the result of
        other inputs than those shown (a value being typed, an invalid one, a
        solve waiting for the pause or running, an error), it names them with
        the values the result is for: never "ready"."""
        status = self.query_one("#status", Static)
        text = Text()
        wanted = self.wanted()
        if self._invalid:
            names = ", ".join(LABELS[n] for n in INPUTS if n in self._invalid)
            text.append(f"invalid {names}", "bold yellow")
        elif self._failed is not None and self._failed[0] == wanted:
            text.append(self._status_error, "bold red")
        elif self._cancelled is not None and self._cancelled == wanted:
            text.append("cancelled (r computes)", "bold yellow")
        elif self._typing:
            names = ", ".join(LABELS[n] for n in INPUTS if n in self._typing)
            text.append(f"typing {names}", "dim")
        elif self.solve_pending or self._in_flight is not None:
            text.append("solving...", "dim")
        stale = self.stale_inputs()
        if stale:
            text.append("; " if text else "")
            text.append("showing the result for " + ", ".join(stale), "yellow")
        elif text and (self._invalid or self._status_error):
            text.append("; showing the last result", "yellow")
        if not text:
            # Every warning of the shown solution (a requested accuracy not met).
            for line in self._warnings:
                text.append(f"warning: {line}  ", "bold yellow")
            if self._hints:
                text.append("hint: " + "; ".join(self._hints) + "  ", "yellow")
            extras = []
            medium = self.result.summary.medium if self.result is not None else ""
            if medium:
                extras.append(f"medium: {medium}")
            if self.overlay is not None:
                values = model.describe(self.overlay.values)
                extras.append(f"overlay {self.overlay.param}: {values}")
            if self.pins:
                extras.append(f"{len(self.pins)} pinned")
            if self._notes:
                extras.append("; ".join(self._notes))
            if extras or not (self._hints or self._warnings):
                text.append("  ".join(extras) or "ready", "dim")
        if text != self._status_shown:  # an update lays the screen out again
            self._status_shown = text
            status.update(text)

    def _set_message(self, name: str, message: str) -> None:
        """The message under the input ``name`` (no update if it shows it)."""
        panel = self.query_one(ParamsPanel)
        if panel.message(name) != message:
            panel.set_message(name, message)

    # -- input --------------------------------------------------------------

    def on_input_changed(self, event: Input.Changed) -> None:
        box_id = event.input.id or ""
        if not box_id.startswith("in-"):
            return
        event.stop()
        name = box_id.removeprefix("in-")
        self._editing = name
        if _still_typing_in(name, event.value):
            # Neither solved nor refused: the user has not finished.
            self._typing.add(name)
            self._invalid.discard(name)
            self._set_message(name, "")
            self._reconcile(soon=True)
            return
        self._typing.discard(name)
        self._accept(name, event.value, soon=True)

    def _accept(self, name: str, text: str, *, soon: bool) -> None:
        """Checks what was typed into ``name`` (an error names the input and
        its range) and applies the rule (``_reconcile``): the inputs shown
        are solved unless the screen shows them, after the user's pause when
        ``soon``."""
        panel = self.query_one(ParamsPanel)
        try:
            params = self._parsed(name, text)
        except InvalidParameterError as exc:
            self._invalid.add(name)
            self._set_message(name, _one_line(exc))
            self._reconcile(soon=soon)
            return
        self._invalid.discard(name)
        self._set_message(name, "")
        if name == "load":
            panel.show_load(params.load)
        self.params = params
        self._show_applicable()
        self._show_gauge()
        self._reconcile(soon=soon)

    def _parsed(self, name: str, text: str) -> Params:
        """The current set with ``text`` typed into ``name``; raises
        InvalidParameterError naming the input and its valid range."""
        if not self.params.applies(name):
            return self.params  # hidden by the medium (ν beside sublayers)
        if name == "profile":
            return replace(self.params, profile=model.parse_profile_kind(text))
        if name == "contact":
            return replace(self.params, contact=model.parse_contact(text))
        if name == "punches":
            train = model.parse_punches(text)
            if [p.text() for p in train] == [p.text() for p in self.params.punches]:
                train = self.params.punches  # keep a scene's own profiles
            return replace(self.params, punches=train)
        return self.params.with_value(name, model.parse_param(name, text))

    def _show_applicable(self) -> None:
        """Shows the inputs that apply to the current set; a hidden input
        loses what was being typed in it (it no longer counts)."""
        panel = self.query_one(ParamsPanel)
        hidden = panel.show_applicable(self.params)
        for name in hidden:
            if name in self._invalid or name in self._typing:
                self._invalid.discard(name)
                self._typing.discard(name)
                self._set_message(name, "")
                panel.set_values(self.params)

    def _finish_typing(self, box: Input) -> None:
        """Enter or leaving an input: what it holds is final (``0.`` is 0,
        an empty box an error), and the inputs shown are solved now unless
        the screen shows them (or is solving them)."""
        name = (box.id or "").removeprefix("in-")
        if name in self._typing:
            self._typing.discard(name)
            self._accept(name, box.value, soon=False)
        else:
            self._reconcile(soon=False)

    def on_input_submitted(self, event: Input.Submitted) -> None:
        if (event.input.id or "").startswith("in-"):
            event.stop()
            self._cancelled = None  # enter solves what is shown
            self._finish_typing(event.input)
            if self.focused is event.input:
                # (not if keys after enter moved the focus on already: a
                # click into another input, ``i``; what is typed there next
                # must not go to the screen's keys, ``e`` Export)
                self.action_leave_input()

    def on_input_blurred(self, event: Input.Blurred) -> None:
        if (event.input.id or "").startswith("in-") and self.is_mounted:
            self._finish_typing(event.input)

    def on_tabbed_content_tab_activated(
        self, event: TabbedContent.TabActivated
    ) -> None:
        event.stop()
        if self.is_mounted and self.generation:
            self._reconcile(soon=False)  # each tab has its own result
            self._sync_plot()

    # -- actions ------------------------------------------------------------

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action == "leave_input":
            # Shown in the footer (and active) only while an input has focus.
            return isinstance(self.focused, Input)
        if action == "cancel":  # escape outside the inputs, while computing
            return self._in_flight is not None and not isinstance(self.focused, Input)
        if action == "edit":  # `i` typed into an input is a letter
            return not isinstance(self.focused, Input)
        if action == "messages":  # shown while a message is shortened
            return any(m.shortened for m in self.query(MessageLine))
        return True

    # Focus moves at once (Screen.set_focus), not later as Widget.focus()
    # does: keys typed right after `i` or Escape while the app is busy
    # drawing go where the user sent them (`i07e` typed 'e' to the screen,
    # which opened the export prompt).
    def action_leave_input(self) -> None:
        self.set_focus(self.query_one("#tabs", TabbedContent).query_one(Tabs))

    def action_cancel(self) -> None:
        """Escape while computing: the user's cancel. The computation stops
        (its token) and the status says so; the inputs are not solved again
        until they change, ``r`` or enter."""
        if self._in_flight is None:
            return
        self._cancelled = self._in_flight
        self._drop_in_flight()
        self.refresh_bindings()
        self._reconcile(soon=False)
        self._sync_plot()

    def action_edit(self) -> None:
        self.set_focus(self.query_one("#in-vstar", Input))

    def action_recompute(self) -> None:
        self._cancelled = None
        self.cache.clear()
        self.request()

    def action_pin(self) -> None:
        if self.result is None:
            self.notify("nothing to pin yet", severity="warning")
            return
        pinned = self.result.summary.params
        if pinned in self.pins:
            self.notify("already pinned")
            return
        self.pins.append(pinned)
        self.notify(f"pinned {pinned.label()}")
        self._reconcile(soon=False)

    def action_clear_pins(self) -> None:
        self.pins.clear()
        self.overlay = None
        self._reconcile(soon=False)

    def _cycle(self, step: int) -> None:
        index = (TABS.index(self.tab) + step) % len(TABS)
        self.action_show_tab(TABS[index])

    def action_next_tab(self) -> None:
        self._cycle(1)

    def action_previous_tab(self) -> None:
        self._cycle(-1)

    def action_show_tab(self, tab: str) -> None:
        self.query_one("#tabs", TabbedContent).active = f"tab-{tab}"

    def action_toggle_quantity(self) -> None:
        self.quantity = "von_mises" if self.quantity == "sigma_x" else "sigma_x"
        self.action_show_tab("field")
        self._reconcile(soon=False)

    def action_toggle_sweep(self) -> None:
        # a/h against load -> radius (-> spacing for a train); on a material
        # given by tau (moving or quasi-static), then a/h and the drag
        # against its speed.
        order = [
            ("load", "a"),
            ("radius", "a"),
            *([("spacing", "a")] if len(self.params.punches) > 1 else []),
        ]
        medium = self.params.medium()
        if medium is not None and medium.speed_dependent:
            order += [("vstar", "a"), ("vstar", "drag")]
        now = (self.sweep.param, self.sweep.quantity)
        param, quantity = (
            order[(order.index(now) + 1) % len(order)] if now in order else order[0]
        )
        if param == "vstar":
            # Four decades around the speed (or from 1e-10 at rest), below
            # the relaxed layer's critical speed (the bound without the
            # inertia; with it a single viscoelastic layer runs on to V*_R,
            # past the range a sweep starts with).
            centre = max(self.params.vstar, 1e-8)
            try:
                top = 0.95 * model.medium_limits(self.params)[0]
            except MovingPunchError:
                top = math.inf
            stop = min(centre * 100.0, top)
            self.sweep = SweepSpec(
                param=param,
                start=min(centre / 100.0, 0.01 * stop),
                stop=stop,
                points=21,
                quantity=quantity,
            )
        else:
            self.sweep = SweepSpec(param=param)
        self.action_show_tab("sweep")
        self._reconcile(soon=False)

    def action_overlay(self) -> None:
        current = self.overlay
        prompt = (
            OverlayPrompt()
            if current is None
            else OverlayPrompt(current.param, model.describe(current.values))
        )
        self.app.push_screen(prompt, self._set_overlay)

    def _set_overlay(self, overlay: Overlay | None) -> None:
        if overlay is not None:
            self.overlay = overlay
            self._reconcile(soon=False)

    def action_medium(self) -> None:
        """The medium editor: the sublayers and the base."""
        self.app.push_screen(MediumEditor(self.params), self._set_medium)

    def _set_medium(self, choice: MediumChoice | None) -> None:
        if choice is None:
            return
        try:
            params = model.with_medium(
                self.params, choice.layers, choice.half_space, choice.inertia
            )
        except InvalidParameterError as exc:  # (the editor checks it first)
            self.notify(_one_line(exc), severity="error")
            return
        panel = self.query_one(ParamsPanel)
        self.params = params
        panel.set_values(params)
        panel.show_medium(params)
        self._show_applicable()
        self._show_gauge()
        self._reconcile(soon=False)

    def action_help(self) -> None:
        self.app.push_screen(HelpScreen())

    def action_messages(self) -> None:
        self.app.push_screen(MessagesScreen(self.query(MessageLine)))

    action_all_messages = action_messages

    def action_quit(self) -> None:
        self._cancel_all()  # the process ends without waiting for a solve
        self.app.exit()

    def on_unmount(self) -> None:
        self._cancel_all()

    def action_figure(self, name: str) -> None:
        try:  # the bundled scene, never a file of that name in the cwd
            scene = scene_files.from_scene(Scene.bundled(name))
        except (MovingPunchError, OSError) as exc:
            self.notify(_one_line(exc), severity="error")
            return
        self.apply(scene, tab=FIGURE_TABS.get(name))

    def apply(self, scene: scene_files.SceneState, tab: TabName | None = None) -> None:
        """Shows a scene: its parameters, overlay and sweep (what was being
        typed is replaced)."""
        self._invalid.clear()
        self._typing.clear()
        self.params = scene.params
        self.overlay = scene.overlay
        self.sweep = scene.sweep or SweepSpec()
        self.query_one(ParamsPanel).set_values(scene.params)
        for name in INPUTS:
            self._set_message(name, "")
        self.query_one(ParamsPanel).show_load(scene.params.load)
        self.query_one(ParamsPanel).show_medium(scene.params)
        self._show_applicable()
        self._show_gauge()
        if tab is not None and tab != self.tab:
            self.action_show_tab(tab)
        self.notify(f"scene {scene.name}" if scene.name else "scene loaded")
        self._reconcile(soon=False)

    def action_open_scene(self) -> None:
        def attempt(path: str, _confirmed: bool) -> str | None:
            state = scene_files.load_in(self.folder, path)
            if scene_files.is_file_name(self.folder, path):
                self._last_file = path  # a file (not a bundled scene's name)
            self.apply(state)
            return None

        self.app.push_screen(
            PathPrompt(
                f"Open a scene (TOML file in {self.folder.label}, or bundled name)",
                self._last_file,
                attempt,
            )
        )

    def action_save_scene(self) -> None:
        state = scene_files.SceneState(
            params=self.params, overlay=self.overlay, sweep=self.sweep, name=""
        )

        def attempt(path: str, confirmed: bool) -> str | None:
            target = self.folder.target(path, overwrite=confirmed)
            try:
                scene_files.save(state, target)
            except OSError as exc:
                return write_error(path, exc)
            self._last_file = path
            self.notify(f"saved {path}")
            return None

        title = f"Save the scene to a file in {self.folder.label}"
        self.app.push_screen(PathPrompt(title, self._last_file, attempt))

    def action_export(self) -> None:
        result = self.results.get(self.tab)
        if result is None or result.request.params != self.params:
            self.notify("nothing computed for this tab yet", severity="warning")
            return
        data = model.to_csv(result.data, result.request.params).encode("utf-8")

        def attempt(path: str, confirmed: bool) -> str | None:
            target = self.folder.target(path, overwrite=confirmed)
            try:
                atomic_write(target, data)
            except OSError as exc:
                return write_error(path, exc)
            self.notify(f"wrote {path}")
            return None

        self.app.push_screen(
            PathPrompt(
                f"Export the visible curves to CSV in {self.folder.label}",
                f"movingpunch-{self.tab}.csv",
                attempt,
            )
        )


NUMERIC_INPUTS = frozenset(INPUTS) - {"profile", "contact", "punches"}

_CHOICES: dict[str, tuple[str, ...]] = {
    "profile": model.TUI_PROFILES,
    "contact": CONTACT_MODES,
}
"""The words the text inputs with a choice take."""


def _still_typing_in(name: str, text: str) -> bool:
    """``text`` in the input ``name`` is not finished yet: a number (see
    ``_still_typing``), the start of one of a choice's words (``cyl``,
    ``au``), or a train ending where more must follow (``0.002@``,
    ``0.002@-1.5,``)."""
    if name in NUMERIC_INPUTS:
        return _still_typing(text)
    t = text.strip().lower()
    if name in _CHOICES:
        words = _CHOICES[name]
        return bool(t) and t not in words and any(w.startswith(t) for w in words)
    if name == "punches" and t:
        last = t.replace(";", ",").split(",")[-1].strip()
        if "@" not in last:  # "" after a comma, or a load before its "@"
            return not last or _still_typing(last) or _is_number(last)
        at = last.split("@", 1)[1].strip()
        return not at or _still_typing(at)
    return False


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _still_typing(text: str) -> bool:
    """A value not finished yet: empty, a number ending where more must
    follow (``0.``, ``1e``, ``1e-``, ``-``), or the start of a word the input
    takes (``inf``, a tolerance preset) that is not yet one."""
    t = text.strip().lower()
    if not t or t[-1] in ".+-":
        return True
    if t[-1] == "e" and (len(t) == 1 or t[-2].isdigit() or t[-2] == "."):
        return True  # an exponent follows
    if t.isalpha():
        return t not in _WORDS and any(w.startswith(t) for w in _WORDS)
    return False


_WORDS = ("inf", "infinity", *PRESETS)
"""The words the numeric inputs take: inf (kw), the tolerance presets."""


def _key(request: Request) -> Request:
    """A request without its generation: what it computes."""
    return replace(request, generation=0)


def _value(params: Params, name: str) -> object:
    """The value of the input ``name`` in ``params`` (a train: its punches'
    texts)."""
    if name == "profile":
        return params.profile
    if name == "contact":
        return params.contact
    if name == "punches":
        return tuple(p.text() for p in params.punches)
    return params.get(name)


def _input_text(params: Params, name: str) -> str:
    """The value of the input ``name`` in ``params`` as the input shows it."""
    if name == "punches":
        return format_punches(params.punches) or "none"
    if name in ("profile", "contact"):
        return str(_value(params, name))
    return fmt(params.get(name), 10)


def _one_line(error: BaseException | None) -> str:
    if error is None:
        return "unknown error"
    return " ".join(str(error).split()) or type(error).__name__


def _zones_text(zones: tuple[tuple[float, float], ...], digits: int) -> str:
    """``[-1.2,-0.3] [0.3,1.2]``: each zone's ends x/h."""
    return " ".join(f"[{fmt(lo, digits)},{fmt(hi, digits)}]" for lo, hi in zones)


def _train_parts(s: model.Summary) -> list[tuple[str, str]]:
    """A train: the punches and zones, then each punch's axis x/h, δ/h and
    zones (compact)."""
    zones = sum(len(p.contact_zones) for p in s.punches)
    parts = [(f"{len(s.punches)} punches", f"{zones} zones")]
    for k, p in enumerate(s.punches, start=1):
        parts.append(
            (
                f"#{k}@{fmt(p.at, 4)}",
                f"δ/h {fmt(p.indentation, 3)} {_zones_text(p.contact_zones, 3)}",
            )
        )
    return parts
