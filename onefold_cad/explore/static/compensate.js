// onefold explore: the Compensate button. It asks /api/compensate/start (the same
// query as /api/state) to compensate the design shown for springback and weight
// (a coarse preview: `onefold compensate`'s search and checks on the coarse mesh),
// polls /api/compensate/progress every second for the progress line and its ETA,
// and when done shows before -> after and loads the compensated design into the
// controls: the design as pressed with the compensated alpha, beta and H on f-line
// (the view, and the Steel view if on, follow). The sliders stay usable while it
// runs: the job goes on for the design as it was when pressed (the progress line
// says which; its result replaces what was moved meanwhile); only Cancel stops it. The server
// computes everything.

const $ = (id) => document.getElementById(id);
const POLL_MS = 1000;

function fmt(x, digits = 4) {
  return x === null || x === undefined ? '–' : String(Number(Number(x).toPrecision(digits)));
}

// query: the current design's query string; load(values): set these controls'
// texts ({alpha: '31.1', ...}: the job's design, compensated or not) and ask for
// the design's state; lawName(law): how the page names a bending law
export function createCompensation({ query, load, lawName }) {
  const button = $('compensate');
  const cancel = $('comp-cancel');
  const back = $('comp-back');
  const status = $('comp-status');
  const panel = $('comp-result');
  let job = null; // the running job's number
  let result = null; // the last finished job's answer
  let showing = 'compensated'; // which values the sliders hold: 'compensated' or 'start'

  function setStatus(text, error = false) {
    status.textContent = text;
    status.classList.toggle('error', error);
  }

  function mark(state) {
    document.body.dataset.compensation = state;
  }

  function running(on) {
    button.disabled = on;
    cancel.hidden = !on;
    cancel.disabled = !on;
  }

  function designText(d) {
    const h = d.hc_fraction === undefined ? '' : `, H ${d.hc_fraction}`;
    return `${d.template || ''} α ${d.alpha}, β ${d.beta}${h}`;
  }

  function row(label, text) {
    const dt = document.createElement('dt');
    dt.textContent = label;
    const dd = document.createElement('dd');
    dd.textContent = text;
    return [dt, dd];
  }

  function showResult(p) {
    const r = p.result;
    const u = r.units;
    const len = (x) => (x === null || x === undefined ? '–' : `${fmt(x)} ${u}`);
    const b = r.before;
    const a = r.after;
    const stands = (f) => (f.stands ? 'stands' : 'does not stand');
    const s = r.start;
    const k = r.compensated;
    const rows = [
      ['max deviation', `${len(b.max_deviation)} → ${len(a.max_deviation)}`],
      ['rms deviation', `${len(b.rms_deviation)} → ${len(a.rms_deviation)}`],
      ['height', `${len(b.height)} → ${len(a.height)} (design ${len(r.designed.height)})`],
      ['span', `${len(b.span)} → ${len(a.span)} (design ${len(r.designed.span)})`],
      ['stands', `${stands(b)} → ${stands(a)}`],
      ['fold to', `α ${fmt(k.alpha, 5)}° (was ${fmt(s.alpha, 5)}), β ${fmt(k.beta, 5)}° (was ${fmt(s.beta, 5)}), `
        + `h_c ${len(k.h_c)} (was ${len(s.h_c)})`],
      ...r.crease.map((c) => [`crease ${c.half}`,
        `fold to ${fmt(c.fold_to_deg)}° (${c.bend}), standing ${fmt(c.after_springback_deg)}°`]),
      ['verdict', r.verdict],
      // what onefold simulate warns of the compensated steel
      ...(r.warnings || []).map((w) => ['warning', w]),
      ['work', `${r.simulations} simulations, ${fmt(r.cpu_s, 3)} s CPU`],
      ['method', `coarse preview with ${lawName(r.law)}: onefold compensate's search `
        + 'and checks on the coarse mesh, without its convergence check; for the normal mesh '
        + '(minutes) download the TOML template and run onefold compensate on it'],
    ];
    panel.querySelector('dl').replaceChildren(...rows.flatMap(([l, t]) => row(l, t)));
    panel.classList.toggle('met', r.reached);
    panel.hidden = false;
  }

  function swap(which) {
    showing = which;
    const done = `compensated (coarse preview) in ${fmt(result.elapsed_s, 3)} s; the sliders hold `;
    if (which === 'compensated') {
      back.textContent = 'Back to uncompensated';
      setStatus(`${done}the compensated values`);
      load(result.result.values);
    } else {
      back.textContent = 'Load compensated';
      setStatus(`${done}the uncompensated values`);
      load(result.result.start_values);
    }
  }

  async function get(url) {
    const res = await fetch(url);
    const ct = res.headers.get('Content-Type') || '';
    if (ct.startsWith('application/json')) return res.json();
    return { ok: false, error: (await res.text()).trim() || `HTTP ${res.status}` };
  }

  function finished(p) {
    job = null;
    running(false);
    if (p.state === 'done') {
      result = p;
      showResult(p);
      const here = new URLSearchParams(query()).get('template');
      if (p.design.template !== undefined && p.design.template !== here) {
        setStatus(`compensated (coarse preview) for template ${p.design.template}: switch back to it `
          + 'to load its values', true);
      } else {
        back.hidden = false;
        swap('compensated');
      }
    } else if (p.state === 'cancelled') {
      setStatus(`compensation cancelled after ${p.simulations} simulations`);
    } else {
      setStatus(p.error || 'compensation failed', true);
    }
    mark(p.state);
  }

  async function poll(number) {
    if (job !== number) return;
    let p;
    try {
      p = await get(`/api/compensate/progress?job=${number}`);
    } catch (err) {
      job = null;
      running(false);
      setStatus(`compensation: no answer from the server (${err})`, true);
      mark('failed');
      return;
    }
    if (job !== number) return;
    if (p.job === undefined) { // refused: the job is gone
      job = null;
      running(false);
      setStatus(p.error, true);
      mark('failed');
      return;
    }
    if (p.state !== 'running') {
      finished(p);
      return;
    }
    // the compensation's last line without its count and ETA (said before it)
    const last = p.lines.length ? p.lines[p.lines.length - 1].replace(/; at most \d+ more, ETA .*$/, '')
      : 'starting';
    const eta = p.eta ? `, ETA ${p.eta}` : '';
    setStatus(`compensating (coarse preview) ${designText(p.design)} as pressed: `
      + `${p.simulations} simulations${eta} · ${last}`);
    document.body.dataset.compensationSimulations = String(p.simulations);
    setTimeout(() => poll(number), POLL_MS);
  }

  async function start() {
    if (job !== null) return;
    running(true);
    panel.hidden = true;
    back.hidden = true;
    setStatus('starting the compensation…');
    mark('starting');
    let p;
    try {
      p = await get(`/api/compensate/start?${query()}`);
    } catch (err) {
      p = { ok: false, error: `compensation: no answer from the server (${err})` };
    }
    if (!p.ok || p.job === undefined) {
      running(false);
      setStatus(p.error, true);
      mark('refused');
      return;
    }
    job = p.job;
    document.body.dataset.compensationJob = String(job);
    mark('running');
    poll(job);
  }

  async function stop() {
    if (job === null) return;
    cancel.disabled = true;
    setStatus('cancelling: the compensation stops at its next simulation…');
    try {
      await get(`/api/compensate/cancel?job=${job}`);
    } catch (err) {
      setStatus(`cancel: no answer from the server (${err})`, true);
    }
  }

  button.addEventListener('click', start);
  cancel.addEventListener('click', stop);
  back.addEventListener('click', () => swap(showing === 'compensated' ? 'start' : 'compensated'));
  running(false);
  back.hidden = true;
  return {};
}
