// onefold explore: the Steel view. While the "Steel" toggle is on, every design the
// page settles on (a slider's release, at once; a typed value or a template, once
// its state arrived) is simulated as steel without a press: /api/steel (the query
// of /api/state) answers what /api/simulate answers, drawn by simulate.js (the
// standing steel coloured by its deviation over the translucent design, the
// numbers). Only the latest design counts: each request is sent at once, the
// server gives up the older ones (steel.py) and an answer for a design the page
// has left is dropped (token). Until the new steel arrives the last one stays,
// marked stale (faint, its numbers greyed) over the new design's paper form: the
// user keeps the form they are shaping in view and sees where the steel of the
// last design stood. Off: the paper view again. The steel comes first, its verdict
// after: while the server's reserve check runs (/api/steel/check, the design of the
// steel shown) "stands" reads "checking…", never a plain yes before the check.
const $ = (id) => document.getElementById(id);

const NAMES = { alpha: 'α', beta: 'β', hc_fraction: 'H on f-line', apex_fraction: 'apex at' };

// the values of `q` that differ from those of `was` ("α 31, thickness 4"), or ''
function changes(q, was) {
  const now = new URLSearchParams(q);
  const old = new URLSearchParams(was || '');
  return [...now].filter(([k, v]) => old.get(k) !== v)
    .map(([k, v]) => `${NAMES[k] || k} ${v.length > 12 ? `${v.slice(0, 12)}…` : v}`).join(', ');
}

// simulation: simulate.js's; render: redraw the 3D view
export function createSteelView({ simulation, render }) {
  const toggle = $('steel');
  let on = false;
  let token = 0; // bumped by every new request and by off: a late answer is dropped
  let current = null; // {q, ok}: the design the page shows
  let asked = null; // the query of the steel asked for (or shown)
  let shown = null; // the query of the steel shown
  let count = 0;
  let said = ''; // the status line of the steel shown
  let checks = 0;
  let verdictDue = false; // the steel shown waits for its reserve check's verdict
  let checkingQ = null; // the design whose check is on its way
  const CHECKING = '; checking whether it stands…';

  function finish(ok, detail) {
    requestAnimationFrame(() => {
      count += 1;
      document.body.dataset.steel = String(count);
      document.body.dataset.steelQuery = ok ? shown : '';
      window.dispatchEvent(new CustomEvent('explore:steel', {
        detail: { ok, done: performance.now(), ...detail },
      }));
    });
  }

  function checked(ok, detail) {
    requestAnimationFrame(() => {
      checks += 1;
      document.body.dataset.steelChecked = String(checks);
      window.dispatchEvent(new CustomEvent('explore:steel-checked', {
        detail: { ok, done: performance.now(), ...detail },
      }));
    });
  }

  // the verdict of the steel shown (design q): applied while that steel is shown
  async function check(q) {
    const started = performance.now();
    checkingQ = q;
    try {
      const res = await fetch(`/api/steel/check?${q}`);
      const json = (res.headers.get('Content-Type') || '').startsWith('application/json');
      const c = json ? await res.json() : { ok: false, error: (await res.text()).trim() };
      if (checkingQ === q) checkingQ = null;
      if (!on || shown !== q) return; // another design's steel is shown meanwhile
      if (c.gone && asked === q) { // the server simulated another design since: ask again
        shown = null;
        asked = null;
        ask(q);
        return;
      }
      if (c.superseded && asked === q) { // given up for a steel request since: check again
        check(q);
        return;
      }
      if (c.ok) {
        verdictDue = false;
        simulation.verdict(c);
        said = said.replace(CHECKING, `; verdict ${((performance.now() - started) / 1000).toFixed(1)} s later`);
        if (asked === q) simulation.setStatus(said);
      } else if (asked === q) {
        simulation.setStatus(c.error || `steel view's check failed (HTTP ${res.status})`, true);
      }
      checked(c.ok, { started, server_ms: c.server_ms ?? null, cpu_ms: c.cpu_ms ?? null });
    } catch (err) {
      if (checkingQ === q) checkingQ = null;
      if (on && shown === q && asked === q) {
        simulation.setStatus(`steel view's check failed: no answer from the server (${err})`, true);
      }
      checked(false, { started });
    }
  }

  async function ask(q) {
    if (q === shown) { // back to the design shown: fresh again, nothing to ask
      token += 1;
      asked = q;
      simulation.markStale(false);
      simulation.setStatus(said);
      render();
      if (verdictDue && checkingQ === null) check(q); // its check was given up meanwhile
      return;
    }
    if (q === asked) return; // on its way
    const mine = ++token;
    asked = q;
    const what = shown === null ? 'this design' : changes(q, shown);
    simulation.markStale(shown !== null);
    simulation.setStatus(`simulating… ${what}${shown === null ? '' : ' (the steel shown is stale)'}`);
    $('sim-status').title = q;
    render();
    const started = performance.now();
    try {
      const res = await fetch(`/api/steel?${q}`);
      const json = (res.headers.get('Content-Type') || '').startsWith('application/json');
      const sim = json ? await res.json() : { ok: false, error: (await res.text()).trim() };
      if (mine !== token) return; // a newer design was asked for meanwhile
      if (sim.ok) {
        simulation.show(sim);
        shown = q;
        const s = ((performance.now() - started) / 1000).toFixed(1);
        const form = sim.mesh.form === 'released' ? '; no standing equilibrium: the released form shown' : '';
        said = `steel of this design in ${s} s (server ${(sim.server_ms / 1000).toFixed(1)} s, `
          + `${sim.level} mesh, ${simulation.lawText(sim.numbers)}, ${sim.numbers.nodes} nodes)`
          + `${form}${sim.numbers.checking ? CHECKING : ''}`;
        simulation.setStatus(said);
        verdictDue = sim.numbers.checking;
        if (verdictDue) check(q);
      } else {
        simulation.clear();
        shown = null;
        asked = null; // a busy server: the same design may be asked again
        simulation.setStatus(sim.superseded ? `steel view: ${sim.error} (another page of this explorer)`
          : sim.error || `steel view failed (HTTP ${res.status})`, true);
      }
      render();
      finish(sim.ok, {
        started, server_ms: sim.server_ms ?? null, cpu_ms: sim.cpu_ms ?? null,
        checking: Boolean(sim.ok && sim.numbers.checking),
      });
    } catch (err) {
      if (mine !== token) return;
      asked = null;
      simulation.setStatus(`steel view failed: no answer from the server (${err})`, true);
      finish(false, { started });
    }
  }

  function follow() {
    if (!on || current === null) return;
    if (current.ok) {
      ask(current.q);
      return;
    }
    token += 1; // nothing to simulate: drop what is on its way
    asked = null;
    shown = null;
    simulation.clear();
    simulation.setStatus('steel view: the design has an error (see the messages)', true);
  }

  function setOn(value) {
    on = value;
    toggle.setAttribute('aria-pressed', String(on));
    document.body.classList.toggle('steel-view', on);
    simulation.setSteel(on);
    token += 1;
    asked = null;
    shown = null;
    simulation.clear(); // off: the paper view; on: the current design's steel next
    render();
    follow();
  }

  toggle.addEventListener('click', () => setOn(!on));

  return {
    // the design is changing (a drag, a state on its way): what is shown is stale
    changing() {
      if (!on) {
        simulation.clear();
      } else if (shown !== null && asked === shown) {
        simulation.markStale(true);
        simulation.setStatus('the design changed: the steel shown is stale');
      }
    },
    // a slider's release: its design's steel at once (its state may be on its way)
    released(q) {
      if (on) ask(q);
    },
    // the page settled on a design (its state arrived, no drag on): its steel next
    settled(q, ok) {
      current = { q, ok };
      follow();
    },
  };
}
