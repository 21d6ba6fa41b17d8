// onefold explore: the Simulate button. It asks /api/simulate (the same query as
// /api/state) for the design as steel on a coarse mesh, then draws the standing
// form coloured by its deviation from the design over the designed form
// (translucent, with its edges), and prints the numbers. The server computes
// everything, colours included; a change of the design clears it. The Steel view
// (steel_view.js) shows its answers with the same drawing (show, markStale).
import * as THREE from 'three';

const $ = (id) => document.getElementById(id);

function decode(b64, Type) {
  const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
}

function fmt(x, digits = 4) {
  return x === null || x === undefined ? '–' : String(Number(Number(x).toPrecision(digits)));
}

// Simulate's law is onefold simulate's (J2); the Steel view's the moment law
const IDLE = 'steel under its own weight, coarse mesh, J2 through the thickness: a few seconds';

// scene: the three.js scene; form: the design's group (hidden while a simulation
// shows: the simulation draws the design on its own mesh); render: redraw;
// query: the current design's query string.
export function createSimulation({ scene, form, render, query }) {
  const group = new THREE.Group();
  scene.add(group);
  const button = $('simulate');
  const status = $('sim-status');
  let token = 0; // bumped by every clear: a late answer for an old design is dropped
  let running = false;
  let enabled = false;
  let steel = false; // the Steel view is on: it simulates every design itself
  let count = 0;
  let ghosts = []; // the design drawn on the simulation's mesh: hidden while stale

  const standingMaterial = new THREE.MeshStandardMaterial({
    vertexColors: true, side: THREE.DoubleSide, metalness: 0.0, roughness: 0.8,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });
  const plainMaterial = new THREE.MeshStandardMaterial({
    color: 0xb8bcc7, side: THREE.DoubleSide, metalness: 0.1, roughness: 0.7,
  });
  const designedMaterial = new THREE.MeshBasicMaterial({
    color: 0x64748b, transparent: true, opacity: 0.22, depthWrite: false, side: THREE.DoubleSide,
  });
  const designedEdges = new THREE.LineBasicMaterial({ color: 0x334155, transparent: true, opacity: 0.8 });
  const materials = [standingMaterial, plainMaterial, designedMaterial, designedEdges];

  // the law the answer was simulated with, as the status names it
  function lawName(law) {
    return law === 'moment' ? 'the moment law' : law === 'j2' ? 'J2 through the thickness' : law;
  }

  // the law and, where so formed, the cones formed past their springback
  function lawText(n) {
    return lawName(n.law) + (n.cone_forming === 'compensated' ? ', cones formed past their springback' : '');
  }

  function setStatus(text, error = false) {
    status.textContent = text;
    status.classList.toggle('error', error);
  }

  function updateButton() {
    button.disabled = running || !enabled || steel;
  }

  // what is shown is for a design the page has left (the Steel view waits for
  // the new one's): the steel faint, its design hidden, the new design's paper
  // form shown, the numbers greyed
  function markStale(stale) {
    for (const m of [standingMaterial, plainMaterial]) {
      m.transparent = stale;
      m.opacity = stale ? 0.35 : 1;
      m.depthWrite = !stale;
      m.needsUpdate = true;
    }
    for (const g of ghosts) g.visible = !stale;
    if (group.children.length) form.visible = stale;
    $('sim-panel').classList.toggle('stale', stale && group.children.length > 0);
  }

  function empty() {
    for (const child of [...group.children]) {
      group.remove(child);
      child.geometry?.dispose();
      if (!materials.includes(child.material)) child.material?.dispose();
    }
    ghosts = [];
    markStale(false);
    form.visible = true;
    $('sim-legend').classList.add('off');
    $('sim-warnings').classList.add('off');
    $('sim-warnings').open = false;
    for (const dd of $('sim-numbers').querySelectorAll('dd')) dd.textContent = '–';
  }

  function geometry(positions, indices) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    g.setIndex(new THREE.BufferAttribute(indices, 1));
    g.computeVertexNormals(); // shading only
    return g;
  }

  function drawLegend(scale) {
    $('sim-scale-label').textContent = `· ${scale.label}`;
    $('sim-min').textContent = fmt(scale.min);
    $('sim-max').textContent = fmt(scale.max);
    const bar = $('sim-scale');
    const ctx = bar.getContext('2d');
    const grad = ctx.createLinearGradient(0, 0, bar.width, 0);
    scale.stops.forEach((c, i) => grad.addColorStop(i / (scale.stops.length - 1), c));
    ctx.fillStyle = grad;
    ctx.fillRect(0, 0, bar.width, bar.height);
    $('sim-legend').classList.remove('off');
  }

  function draw(sim) {
    const m = sim.mesh;
    const IndexType = m.index_type === 'uint16' ? Uint16Array : Uint32Array;
    const indices = decode(m.indices, IndexType);
    const designed = geometry(decode(m.designed, Float32Array), indices);
    const ghost = new THREE.Mesh(designed, designedMaterial);
    ghost.renderOrder = 1; // after the opaque form: seen through
    ghosts = [ghost, new THREE.LineSegments(new THREE.EdgesGeometry(designed, 40), designedEdges)];
    group.add(...ghosts);
    if (m.positions) {
      const shown = geometry(decode(m.positions, Float32Array), indices);
      let material = plainMaterial;
      if (m.colours) {
        const bytes = decode(m.colours, Uint8Array);
        const linear = new Float32Array(bytes.length);
        const c = new THREE.Color();
        for (let i = 0; i < bytes.length; i += 3) {
          c.setRGB(bytes[i] / 255, bytes[i + 1] / 255, bytes[i + 2] / 255, THREE.SRGBColorSpace);
          linear[i] = c.r; linear[i + 1] = c.g; linear[i + 2] = c.b;
        }
        shown.setAttribute('color', new THREE.BufferAttribute(linear, 3));
        material = standingMaterial;
      }
      group.add(new THREE.Mesh(shown, material));
    }
    form.visible = false;
    if (sim.scale) drawLegend(sim.scale);
  }

  function showNumbers(sim) {
    const n = sim.numbers;
    const u = sim.units;
    const len = (x) => (x === null || x === undefined ? '–' : `${fmt(x)} ${u}`);
    $('sim-deviation').textContent = n.max_deviation === null ? '– (no standing equilibrium)'
      : `max ${len(n.max_deviation)}, rms ${len(n.rms_deviation)}`;
    $('sim-stands').textContent = n.checking ? 'checking… (the coarse preview\'s reserve)'
      : n.uncertain ? `uncertain: ${n.uncertain}`
      : n.stands
        ? `yes${n.tipping_margin_deg === null ? '' : ` (tipping margin ${fmt(n.tipping_margin_deg, 3)}°)`}`
        : `no: ${n.reason}`;
    $('sim-size').textContent = `${len(n.height)} · ${len(n.span)}`;
    $('sim-springback').textContent = n.springback_max_deviation === null ? '–'
      : `max deviation ${len(n.springback_max_deviation)}`;
    $('sim-plastic').textContent = n.plastic_area_share === null ? '–'
      : `${fmt(100 * n.plastic_area_share, 3)} % of the area`;
    // past yield the moment law's stress is its elastic estimate, not a stress
    // the steel can be in (the stress picture and the warning say the same)
    // J2's stress past yield is the hardened flow stress at its plastic strain
    const estimate = n.utilisation <= 1 ? ''
      : n.law === 'moment' ? '; past yield the moment law\'s elastic estimate'
      : n.law === 'j2' ? '; the flow stress, hardened past yield' : '';
    $('sim-stress').textContent = n.max_stress_MPa === null ? '–'
      : `${fmt(n.max_stress_MPa)} MPa (${fmt(n.utilisation, 3)} × yield ${fmt(n.yield_stress_MPa)} MPa${estimate})`;
    const box = $('sim-warnings');
    const list = box.querySelector('ul');
    list.replaceChildren(...sim.warnings.map((w) => {
      const li = document.createElement('li');
      li.textContent = w;
      return li;
    }));
    box.querySelector('summary').textContent = `${sim.warnings.length} warning${sim.warnings.length === 1 ? '' : 's'}`;
    box.classList.toggle('off', sim.warnings.length === 0);
  }

  function finish(ok, sim = null) {
    requestAnimationFrame(() => {
      count += 1;
      document.body.dataset.simulations = String(count);
      window.dispatchEvent(new CustomEvent('explore:simulated', {
        detail: { ok, server_ms: sim?.server_ms ?? null, cpu_ms: sim?.cpu_ms ?? null },
      }));
    });
  }

  async function simulate() {
    if (running || !enabled) return;
    const mine = ++token;
    const q = query();
    running = true;
    updateButton();
    empty();
    render();
    setStatus('simulating (coarse mesh)…');
    const started = performance.now();
    let ok = false;
    let sim = null;
    try {
      const res = await fetch(`/api/simulate?${q}`);
      sim = await res.json();
      if (mine !== token) return; // the design changed meanwhile
      if (!sim.ok) {
        setStatus(sim.error || `simulation failed (HTTP ${res.status})`, true);
      } else {
        draw(sim);
        showNumbers(sim);
        const s = ((performance.now() - started) / 1000).toFixed(1);
        const form = sim.mesh.form === 'released' ? '; no standing equilibrium: the released form shown' : '';
        setStatus(`simulated in ${s} s (${sim.level} mesh, ${lawText(sim.numbers)}, ${sim.numbers.nodes} nodes)${form}`);
        ok = true;
      }
      render();
    } catch (err) {
      if (mine === token) setStatus(`simulation failed: no answer from the server (${err})`, true);
    } finally {
      running = false;
      updateButton();
      if (mine === token) finish(ok, sim);
    }
  }

  button.addEventListener('click', simulate);

  return {
    // the design changed: drop what is shown (and what is on its way)
    clear() {
      token += 1;
      empty();
      setStatus(steel ? '' : IDLE);
    },
    // the Steel view's answer: drawn and numbered as a press's
    show(sim) {
      token += 1;
      empty();
      draw(sim);
      showNumbers(sim);
    },
    // the Steel view's reserve check of the steel shown: its verdict and warnings
    verdict(check) {
      showNumbers(check);
    },
    markStale,
    setStatus,
    lawName,
    lawText,
    // the Steel view is on (the button waits) or off
    setSteel(on) {
      steel = on;
      updateButton();
    },
    // the current design can be simulated only when it solved
    setEnabled(on) {
      enabled = on;
      updateButton();
    },
  };
}
