"""Runs sharing one catalogue compute each path set once.

A run claims the path sets it is missing (catalogue.store: claims) and computes those it
gets; the sets another live run holds it waits for, polling the catalogue every POLL_S
seconds, and takes them as that run stores them.  A set whose owner ended without it
(Ctrl-C, killed, lost scheduler) or went silent is claimed and computed here; a set its
owner failed on is failed here too, with that run's reason.  The owner refreshes its
claims at most every REFRESH_S seconds while it computes, releases each as its set is
stored or failed, and all of them when it ends, however it ends.

Times in seconds.
"""
import time

from . import interrupt

POLL_S = 1.0            # a waiting run looks at the catalogue this often
REFRESH_S = 5.0         # an owner's claims get a sign of life at most this often
STALE_MIN_S = 60.0      # a claim silent this long (or the study's task_timeout_s) is stale
WAIT_LIMIT_S = 12 * 3600.0  # a waiting run gives up on a live, busy owner after this long
SAY_EVERY_S = 60.0      # a waiting run says so this often


def stale_after(task_timeout_s: float) -> float:
    """Seconds without a sign of life after which another run's claim is taken over: the
    study's task timeout (no task of a live owner runs longer), at least STALE_MIN_S."""
    return max(float(task_timeout_s), STALE_MIN_S)


class Claims:
    """The claims of run `run` (the catalogue's runs table) of `study` in `cat`."""

    def __init__(self, cat, run: int, study: str, stale_s: float):
        self.cat, self.run, self.study, self.stale_s = cat, run, study, stale_s
        self._refreshed = time.monotonic()

    def take(self, shells) -> dict:
        """Claim `shells`' sets: {fingerprint: Claim} of those another live run holds."""
        self._refreshed = time.monotonic()
        return self.cat.claim([s.fingerprint for s in shells], self.run, self.study,
                              self.stale_s)

    def refresh(self):
        """A sign of life, at most every REFRESH_S seconds (call it as often as you like)."""
        if time.monotonic() - self._refreshed >= REFRESH_S:
            self.cat.refresh_claims(self.run)
            self._refreshed = time.monotonic()

    def settled(self, fingerprint: str):
        """The set `fingerprint` is stored or has failed: its claim goes."""
        self.cat.release_claims(self.run, [fingerprint])

    def release(self):
        """Every claim of this run goes (at its end)."""
        self.cat.release_claims(self.run)


def settle(shells, claims: Claims, compute, progress, tally) -> dict:
    """Have every set of `shells` computed once: `compute(shells)` those this run claims
    (it stores them or records their failure in `tally`); wait for those other runs hold.
    Returns {fingerprint: (Entry, Dataset)} of the sets other runs stored; a set another
    run failed on, or still held after WAIT_LIMIT_S, goes to tally.failed."""
    shared, todo = {}, list(shells)
    # each round computes what it claims; a new round needs a set whose owner ended
    # without it, which this run then claims (or a third run did first)
    for _ in range(2 * len(shells) + 1):
        if not todo:
            break
        held = claims.take(todo)
        for claim in claims.cat.taken_over:
            progress.say(f"took over path set {claim.fingerprint[:12]} from {claim}: that "
                         "run ended or went silent")
        claims.cat.taken_over.clear()
        mine = []
        for s in todo:
            if s.fingerprint in held:
                continue
            hit = claims.cat.fetch(s.key)     # stored by a run that ended since we looked
            if hit is None:
                mine.append(s)
            else:
                claims.settled(s.fingerprint)
                _arrived(s, hit, shared, progress)
        if mine:
            compute(mine)
        todo = _wait([s for s in todo if s.fingerprint in held], held, claims, progress,
                     tally, shared)
    for s in todo:
        tally.failed[s.fingerprint] = ("claimed by other runs that each ended without it; "
                                       "run again")
    return shared


def _wait(shells, held: dict, claims: Claims, progress, tally, shared) -> list:
    """Wait until each of `shells` (held by the runs of `held`: fingerprint -> Claim) is
    stored (into `shared`), failed by its owner (into tally.failed) or free; returns the
    shells still to compute as soon as one is free, else []."""
    if not shells:
        return []
    cat, t0 = claims.cat, time.monotonic()
    said = None
    while True:                 # bounded: WAIT_LIMIT_S
        interrupt.check()       # Ctrl-C while waiting: nothing of this run is in flight
        free, waiting = [], []
        for s in shells:
            fp = s.fingerprint
            hit = cat.fetch(s.key)
            if hit is not None:
                _arrived(s, hit, shared, progress)
                continue
            now = cat.claim_of(fp)
            if now is None or now.run != held[fp].run:
                reason = cat.failure_by(held[fp])
                if reason is not None:
                    tally.failed[fp] = f"failed in {held[fp]}: {reason}"
                    progress.update("loading paths", advance=1)
                    progress.update("relaxation paths", advance=1)
                    continue
            if now is None or now.stale(claims.stale_s):
                free.append(s)
                continue
            held[fp] = now
            waiting.append(s)
        if free or not waiting:
            return free + waiting
        elapsed = time.monotonic() - t0
        if elapsed > WAIT_LIMIT_S:
            for s in waiting:
                tally.failed[s.fingerprint] = (
                    f"still computed by {held[s.fingerprint]} after waiting "
                    f"{elapsed:.0f} s; run again when it has ended")
            return []
        if said is None or time.monotonic() - said >= SAY_EVERY_S:
            owners = "; ".join(sorted({str(held[s.fingerprint]) for s in waiting}))
            progress.say(f"waiting for {len(waiting)} path set{'s' if len(waiting) > 1 else ''} "
                         f"that another run is computing, {owners}: {elapsed:.0f} s so far "
                         f"(a set whose run ends without it, or is silent for "
                         f"{claims.stale_s:g} s, is computed here)")
            said = time.monotonic()
        shells = waiting
        time.sleep(POLL_S)


def _arrived(shell, hit, shared, progress):
    """The set of `shell`, stored by another run (`hit`: Entry, Dataset), is served."""
    shared[shell.fingerprint] = hit
    progress.update("loading paths", advance=1)
    progress.update("relaxation paths", advance=1, note=f"{len(shared)} stored by another run")
