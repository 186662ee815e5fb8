// gibench report: renders window.GIB_RESULTS (results.js) and window.GIB_IMG (img/*.js, float
// RGB for the exposure control) into #app. Plain JS, no network: opens from disk.
// Test hook: document.body.dataset.gibStatus = "ok" once everything rendered and every <img>
// loaded; "error: <what>" on the first image or script error (also logged with console.error).
(function () {
  'use strict';

  // ---------------------------------------------------------------- status (the test hook)
  var failedWith = null;
  var reported = {};
  function fail(what) {
    what = String(what);
    if (!reported[what]) {
      reported[what] = true;
      console.error('gibench report error: ' + what);
    }
    if (failedWith === null) {
      failedWith = what;
      document.body.dataset.gibStatus = 'error: ' + what;
      showErrorBanner(what);
    }
  }
  window.GIB_REPORT_FAIL = fail;

  function showErrorBanner(what) {
    var bar = document.getElementById('gib-load-errors');
    if (!bar) {
      bar = h('div', { id: 'gib-load-errors', class: 'load-errors' }, [h('strong', null, 'Report problem: ')]);
      document.body.insertBefore(bar, document.body.firstChild);
    }
    bar.appendChild(h('span', { class: 'load-error' }, what));
  }

  // ---------------------------------------------------------------- DOM helpers
  function h(tag, attrs, children) {
    var el = document.createElement(tag);
    if (attrs) {
      for (var k in attrs) {
        if (!Object.prototype.hasOwnProperty.call(attrs, k)) continue;
        var v = attrs[k];
        if (v === null || v === undefined || v === false) continue;
        if (k === 'class') el.className = v;
        else if (k === 'text') el.textContent = v;
        else if (k.slice(0, 2) === 'on') el.addEventListener(k.slice(2), v);
        else if (k === 'style' && typeof v === 'object') for (var s in v) el.style[s] = v[s];
        else el.setAttribute(k, v === true ? '' : v);
      }
    }
    append(el, children);
    return el;
  }
  function append(el, children) {
    if (children === null || children === undefined) return;
    if (Array.isArray(children)) { children.forEach(function (c) { append(el, c); }); return; }
    if (typeof children === 'string' || typeof children === 'number') el.appendChild(document.createTextNode(String(children)));
    else el.appendChild(children);
  }
  function slug(s) { return String(s).replace(/[^A-Za-z0-9_-]+/g, '-'); }

  // ---------------------------------------------------------------- number formatting
  function fmtNum(v, digits) {
    if (v === null || v === undefined || typeof v !== 'number') return '\u2014';
    if (!isFinite(v)) return v > 0 ? '\u221e' : (v < 0 ? '-\u221e' : 'NaN');
    if (digits !== undefined) return v.toFixed(digits);
    var a = Math.abs(v);
    if (a === 0) return '0';
    if (a < 1e-3 || a >= 1e6) return v.toExponential(2);
    if (Number.isInteger(v)) return String(v);
    return String(parseFloat(v.toPrecision(4)));
  }
  function fmtMs(v) {
    if (typeof v !== 'number' || !isFinite(v)) return '\u2014';
    return v < 0.1 ? v.toFixed(3) : v < 10 ? v.toFixed(2) : v.toFixed(1);
  }
  function fmtBytes(b) {
    if (typeof b !== 'number' || !isFinite(b)) return '\u2014';
    var u = ['B', 'KiB', 'MiB', 'GiB'], i = 0;
    while (b >= 1024 && i < u.length - 1) { b /= 1024; ++i; }
    return (i ? b.toFixed(1) : String(b)) + ' ' + u[i];
  }
  function metric(row, name) {
    var m = row.metrics || {};
    return Object.prototype.hasOwnProperty.call(m, name) ? m[name] : undefined;
  }

  // ---------------------------------------------------------------- images
  var LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;
  var decoded = {};  // id -> {w, h, px: Float32Array RGB} | null (use the PNG)
  function floatImage(id) {
    if (Object.prototype.hasOwnProperty.call(decoded, id)) return decoded[id];
    var src = (window.GIB_IMG || {})[id];
    var out = null;
    if (src && typeof src.data === 'string') {
      var bin = atob(src.data);
      var n = src.w * src.h * 3;
      if (bin.length !== n * 4) {
        fail('img/' + id + '.js: ' + bin.length + ' bytes of data, expected ' + (n * 4) + ' for ' + src.w + 'x' + src.h + ' RGB float32');
      } else {
        var bytes = new Uint8Array(bin.length);
        for (var i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
        var px;
        if (LITTLE_ENDIAN) px = new Float32Array(bytes.buffer);
        else {
          px = new Float32Array(n);
          var dv = new DataView(bytes.buffer);
          for (var j = 0; j < n; ++j) px[j] = dv.getFloat32(j * 4, true);
        }
        out = { w: src.w, h: src.h, px: px };
      }
    }
    decoded[id] = out;
    return out;
  }

  // Linear [0,1] -> sRGB 8 bit, through a table (exposure is applied before the lookup).
  var LUT_N = 16384;
  var SRGB_LUT = new Uint8ClampedArray(LUT_N + 1);
  for (var li = 0; li <= LUT_N; ++li) {
    var lin = li / LUT_N;
    var enc = lin <= 0.0031308 ? 12.92 * lin : 1.055 * Math.pow(lin, 1 / 2.4) - 0.055;
    SRGB_LUT[li] = Math.round(enc * 255);
  }
  function drawFloat(canvas, img, ev) {
    var ctx = canvas.getContext('2d');
    var data = ctx.createImageData(img.w, img.h);
    var d = data.data, px = img.px, scale = Math.pow(2, ev) * LUT_N;
    for (var p = 0, q = 0; p < px.length; p += 3, q += 4) {
      var r = px[p], g = px[p + 1], b = px[p + 2];
      if (r !== r || g !== g || b !== b) {  // NaN: flag it in magenta
        d[q] = 255; d[q + 1] = 0; d[q + 2] = 255;
      } else {
        r *= scale; g *= scale; b *= scale;
        d[q] = SRGB_LUT[r >= LUT_N ? LUT_N : r > 0 ? r | 0 : 0];
        d[q + 1] = SRGB_LUT[g >= LUT_N ? LUT_N : g > 0 ? g | 0 : 0];
        d[q + 2] = SRGB_LUT[b >= LUT_N ? LUT_N : b > 0 ? b | 0 : 0];
      }
      d[q + 3] = 255;
    }
    ctx.putImageData(data, 0, 0);
  }

  var pendingImages = [];
  function loadImg(src, alt) {
    var img = new Image();
    var done;
    pendingImages.push(new Promise(function (resolve) { done = resolve; }));
    img.onload = function () { done(); };
    img.onerror = function () {
      fail('failed to load ' + src);
      var fig = img.closest('.frame');
      if (fig) fig.classList.add('missing');
      done();
    };
    img.alt = alt;
    img.decoding = 'async';
    img.src = src;
    return img;
  }

  // One image panel: a canvas from the float data (exposure-controlled) or the PNG preview;
  // ROI outlines in normalised coordinates; a crosshair for the linked pixel readout.
  function figure(opts) {
    var frame = h('div', { class: 'frame' });
    var fl = opts.floatId ? floatImage(opts.floatId) : null;
    var media;
    if (fl) {
      media = h('canvas', { width: fl.w, height: fl.h, class: 'media', 'data-img': opts.floatId });
      opts.caseState.canvases.push({ canvas: media, img: fl });
      drawFloat(media, fl, opts.caseState.ev);
      frame.style.aspectRatio = fl.w + ' / ' + fl.h;
    } else {
      media = loadImg(opts.png, opts.label);
      media.className = 'media' + (opts.floatId ? ' fallback' : '');
      if (opts.w && opts.h) frame.style.aspectRatio = opts.w + ' / ' + opts.h;
    }
    frame.appendChild(media);
    frame.appendChild(h('div', { class: 'missing-note' }, 'missing: ' + opts.png));
    (opts.rois || []).forEach(function (r) {
      frame.appendChild(h('div', {
        class: 'roi',
        title: 'ROI ' + r.name,
        style: {
          left: (r.x0 * 100) + '%', top: (r.y0 * 100) + '%',
          width: ((r.x1 - r.x0) * 100) + '%', height: ((r.y1 - r.y0) * 100) + '%'
        }
      }, h('span', { class: 'roi-label' }, r.name)));
    });
    var cross = h('div', { class: 'cross' });
    frame.appendChild(cross);
    var tag = fl ? h('span', { class: 'tag hdr', title: 'drawn from float data: the exposure slider applies' }, 'HDR')
      : opts.floatId ? h('span', { class: 'tag png', title: 'no float data (img/' + opts.floatId + '.js): fixed-exposure PNG preview' }, 'PNG')
        : null;
    return {
      el: h('figure', { class: 'panel ' + (opts.kind || '') }, [
        h('figcaption', null, [h('span', { class: 'cap' }, opts.label), tag]),
        frame,
        opts.legend || null
      ]),
      frame: frame, cross: cross, floatImg: fl
    };
  }

  function magmaLegend() {
    return h('div', { class: 'legend' }, [
      h('span', null, '0'), h('span', { class: 'ramp' }), h('span', null, '1')
    ]);
  }

  // Reference | output | FLIP error map, with a linked crosshair and a pixel readout.
  function imageRow(row, c, cs) {
    var w = c ? c.width : 0, hh = c ? c.height : 0, rois = c ? c.rois : [];
    var panels = [];
    if (row.reference_image) {
      panels.push(figure({ label: 'reference', floatId: row.reference_image, png: 'img/' + row.reference_image + '.png',
        rois: rois, caseState: cs, w: w, h: hh, kind: 'ref' }));
    }
    if (row.image) {
      panels.push(figure({ label: row.kind === 'negative_control' ? 'negative control output' : 'output',
        floatId: row.image, png: 'img/' + row.image + '.png', rois: rois, caseState: cs, w: w, h: hh, kind: 'out' }));
      if (row.reference_image) {
        panels.push(figure({ label: 'FLIP error vs reference', png: 'img/' + row.image + '.flip.png', rois: rois,
          caseState: cs, w: w, h: hh, kind: 'flip', legend: magmaLegend() }));
      }
    }
    (row.views || []).forEach(function (v) {
      panels.push(figure({ label: 'view: ' + v.name, floatId: v.image, png: 'img/' + v.image + '.png',
        rois: [], caseState: cs, w: w, h: hh, kind: 'view' }));
    });
    if (!panels.length) return h('p', { class: 'muted' }, 'No images for this row.');
    var readout = h('div', { class: 'readout' }, 'Hover an image for linear pixel values.');
    function move(ev) {
      var rect = ev.currentTarget.getBoundingClientRect();
      var u = (ev.clientX - rect.left) / rect.width, v = (ev.clientY - rect.top) / rect.height;
      if (u < 0 || v < 0 || u >= 1 || v >= 1) return;
      var iw = w, ih = hh;
      panels.forEach(function (p) { if (p.floatImg) { iw = p.floatImg.w; ih = p.floatImg.h; } });
      var x = Math.floor(u * iw), y = Math.floor(v * ih);
      panels.forEach(function (p) {
        p.cross.style.display = 'block';
        p.cross.style.left = ((x + 0.5) / iw * 100) + '%';
        p.cross.style.top = ((y + 0.5) / ih * 100) + '%';
      });
      var parts = [h('span', { class: 'xy' }, 'x ' + x + '  y ' + y)];
      panels.forEach(function (p) {
        if (!p.floatImg || x >= p.floatImg.w || y >= p.floatImg.h) return;
        var i = (y * p.floatImg.w + x) * 3, px = p.floatImg.px;
        parts.push(h('span', null, [h('b', null, p.el.querySelector('.cap').textContent + ' '),
          fmtNum(px[i]) + '  ' + fmtNum(px[i + 1]) + '  ' + fmtNum(px[i + 2])]));
      });
      readout.textContent = '';
      append(readout, parts);
    }
    function leave() { panels.forEach(function (p) { p.cross.style.display = 'none'; }); }
    panels.forEach(function (p) {
      p.frame.addEventListener('mousemove', move);
      p.frame.addEventListener('mouseleave', leave);
    });
    return h('div', { class: 'images-wrap' }, [
      h('div', { class: 'images n' + panels.length }, panels.map(function (p) { return p.el; })),
      readout
    ]);
  }

  // ---------------------------------------------------------------- status badges
  // not_run: a row the run's profile (e.g. quick) left out. Grey, never counted as passed.
  function badge(row) {
    var neg = row.kind === 'negative_control';
    var s = row.status || 'error';
    if (s === 'not_run') {
      return h('span', { class: 'badge not_run', title: (row.messages || [])[0] || 'not run by this profile' }, 'not run');
    }
    var label = neg ? (s === 'pass' ? 'caught' : s === 'fail' ? 'NOT caught' : s === 'skipped' ? 'skipped' : 'error') : s === 'known_failure' ? 'known failure' : s;
    return h('span', { class: 'badge ' + s, title: neg ? 'negative control: status pass means a threshold caught it' : null }, label);
  }

  function optionsText(o) {
    var keys = Object.keys(o || {});
    if (!keys.length) return '';
    return keys.map(function (k) { return k + '=' + fmtNum(o[k]); }).join(' \u00b7 ');
  }

  function rowAnchor(row, i) { return 'row-' + slug(row.case) + '-' + i; }

  // ---------------------------------------------------------------- checks
  function checksList(row) {
    var checks = row.checks || [];
    // In a negative control a failed check is the point: it is what caught the break.
    var neg = row.kind === 'negative_control';
    if (!checks.length) return h('p', { class: 'muted' }, 'No checks.');
    return h('ul', { class: 'checks' }, checks.map(function (c) {
      var bound = [];
      if (typeof c.max === 'number') bound.push('\u2264 ' + fmtNum(c.max));
      if (typeof c.min === 'number') bound.push('\u2265 ' + fmtNum(c.min));
      // Gauge: value relative to the bound, the bound at two thirds of the width.
      var thr = typeof c.max === 'number' ? c.max : c.min;
      var frac = (typeof c.value === 'number' && isFinite(c.value) && thr) ? Math.max(0, Math.min(1.5, c.value / thr)) / 1.5
        : (typeof c.value === 'number' && isFinite(c.value) ? 0 : 1);
      var name = c.metric + (c.against ? ' vs ' + c.against : '') + (c.roi ? ' [' + c.roi + ']' : '');
      var cls = c.skipped ? 'skipped' : c.pass ? 'pass' : neg ? 'fail caught' : 'fail';
      return h('li', { class: cls, title: c.message || '' }, [
        h('span', { class: 'icon' }, c.skipped ? '\u2013' : c.pass ? '\u2713' : '\u2717'),
        h('span', { class: 'cname' }, [name, !c.pass && neg ? h('span', { class: 'caught-tag' }, 'caught it') : null]),
        h('span', { class: 'gauge' }, [h('span', { class: 'fill', style: { width: (frac * 100) + '%' } }), h('span', { class: 'thr' })]),
        h('span', { class: 'cval' }, c.skipped ? 'skipped' : fmtNum(c.value)),
        h('span', { class: 'cbound' }, bound.join(' ') || '\u2014'),
        c.pass && !c.skipped ? null : h('div', { class: 'cmsg' }, c.message || '')
      ]);
    }));
  }

  // ---------------------------------------------------------------- passes and plan
  function passBars(row, maxMs) {
    var passes = row.passes || [];
    var ran = passes.filter(function (p) { return p.status === 'ran'; });
    var culled = passes.filter(function (p) { return p.status !== 'ran'; });
    var out = [];
    if (ran.length) {
      out.push(h('div', { class: 'bars' }, ran.map(function (p) {
        var ms = typeof p.ms === 'number' ? p.ms : 0;
        var pct = maxMs > 0 ? Math.max(0.5, ms / maxMs * 100) : 0;
        var tip = p.name + ': median ' + fmtMs(p.ms) + ' ms' +
          (typeof p.min_ms === 'number' ? ', min ' + fmtMs(p.min_ms) + ', max ' + fmtMs(p.max_ms) : '');
        return h('div', { class: 'bar-row', title: tip }, [
          h('span', { class: 'bar-name' }, p.name),
          h('span', { class: 'bar-track' }, [
            h('span', { class: 'bar', style: { width: pct + '%' } }),
            typeof p.min_ms === 'number' && maxMs > 0 ? h('span', {
              class: 'bar-range',
              style: { left: (p.min_ms / maxMs * 100) + '%', width: (Math.max(0, p.max_ms - p.min_ms) / maxMs * 100) + '%' }
            }) : null
          ]),
          h('span', { class: 'bar-ms' }, typeof p.ms === 'number' ? fmtMs(p.ms) + ' ms' : 'no timing')
        ]);
      })));
    } else {
      out.push(h('p', { class: 'muted' }, 'No pass ran.'));
    }
    if (culled.length) {
      out.push(h('div', { class: 'plan-head' }, 'Culled by the plan'));
      out.push(h('ul', { class: 'culled' }, culled.map(function (p) {
        return h('li', null, [h('span', { class: 'bar-name' }, p.name), h('span', { class: 'reason' }, p.reason || 'culled')]);
      })));
    }
    var t = row.timing;
    var timed = t ? ' (median of ' + t.frames + (t.scan_free ? ' scan-free' : ' scanned') + ' frames after ' + t.warmup + ')' : '';
    out.push(h('div', { class: 'plan-foot' }, [
      ran.length + ' ran, ' + culled.length + ' culled \u00b7 frame ' + fmtMs(row.gpu_ms) + ' ms' + timed +
        ' \u00b7 resources ' + fmtBytes(row.resource_bytes)
    ]));
    return out;
  }

  // ---------------------------------------------------------------- stability
  function svgEl(tag, attrs, children) {
    var el = document.createElementNS('http://www.w3.org/2000/svg', tag);
    Object.keys(attrs || {}).forEach(function (k) { el.setAttribute(k, attrs[k]); });
    (children || []).forEach(function (ch) {
      if (ch) el.appendChild(typeof ch === 'string' ? document.createTextNode(ch) : ch);
    });
    return el;
  }

  // Convergence: the ROI mean divided by the target, per frame, with the +-5% band.
  function convergencePlot(row) {
    var curve = row.curve || [];
    var t = row.curve_target;
    if (curve.length < 2 || !(t > 0)) return null;
    var W = 420, H = 150, L = 44, R = 8, T = 8, B = 24;
    var ys = curve.map(function (v) { return v === null ? NaN : v / t; });
    var finite = ys.filter(function (v) { return isFinite(v); });
    var lo = Math.min(0.9, Math.min.apply(null, finite.concat([1])));
    var hi = Math.max(1.1, Math.max.apply(null, finite.concat([1])));
    function X(i) { return L + (W - L - R) * i / (curve.length - 1); }
    function Y(v) { return T + (H - T - B) * (1 - (v - lo) / (hi - lo)); }
    var d = '';
    ys.forEach(function (v, i) { if (isFinite(v)) d += (d ? 'L' : 'M') + X(i).toFixed(1) + ' ' + Y(v).toFixed(1); });
    var kids = [
      svgEl('rect', { x: L, y: Y(1.05), width: W - L - R, height: Math.max(0, Y(0.95) - Y(1.05)), class: 'band' }),
      svgEl('line', { x1: L, x2: W - R, y1: Y(1), y2: Y(1), class: 'target' }),
      svgEl('path', { d: d, class: 'curve' }),
      svgEl('text', { x: L - 4, y: Y(hi) + 10, 'text-anchor': 'end' }, [hi.toFixed(2)]),
      svgEl('text', { x: L - 4, y: Y(1) + 4, 'text-anchor': 'end' }, ['1.00']),
      svgEl('text', { x: L - 4, y: Y(lo), 'text-anchor': 'end' }, [lo.toFixed(2)]),
      svgEl('text', { x: L, y: H - 6 }, ['frame 1']),
      svgEl('text', { x: W - R, y: H - 6, 'text-anchor': 'end' }, ['frame ' + curve.length])
    ];
    return svgEl('svg', { class: 'conv', viewBox: '0 0 ' + W + ' ' + H, width: W, height: H,
      'aria-label': 'ROI mean / target per frame' }, kids);
  }

  // Per resource scan counts (NaN/Inf/negative/above bound/at format max) and the first offenders.
  function stabilitySection(row) {
    var st = row.stability;
    var plot = convergencePlot(row);
    var m = row.metrics || {};
    var figures = ['flicker', 'conv_error_final', 'conv_error_max', 'conv_drift', 'conv_oscillation']
      .filter(function (k) { return k in m; })
      .map(function (k) { return h('span', { class: 'kv' }, [k + ' ', h('b', null, fmtNum(m[k], 4))]); });
    if (!st && !plot && !figures.length) return null;
    var out = [h('h5', null, 'Stability')];
    if (figures.length) out.push(h('div', { class: 'figures' }, figures));
    if (plot) out.push(h('div', { class: 'plot' }, [plot, h('div', { class: 'muted' },
      'ROI mean / target per frame (band: \u00b15%)')]));
    if (st) {
      var recs = st.resources || [];
      out.push(h('p', null, st.scanned ? (recs.length ? '' : 'GPU scan: every written resource finite and in range on every frame.')
        : 'GPU scan off.'));
      (st.first_offenders || []).forEach(function (f) { out.push(h('p', { class: 'offender' }, f)); });
      if (recs.length) {
        out.push(h('table', { class: 'stability' }, [
          h('thead', null, h('tr', null, ['pass', 'resource', 'NaN', 'Inf', 'negative', 'above bound', 'at format max', 'first frame', 'first at']
            .map(function (t) { return h('th', null, t); }))),
          h('tbody', null, recs.map(function (r) {
            return h('tr', null, [r.pass, r.resource, r.nan, r.inf, r.negative, r.above_max, r.saturated, r.first_frame, r.first_at]
              .map(function (v) { return h('td', null, v === undefined || v === null ? '' : String(v)); }));
          }))
        ]));
      }
    }
    return h('section', { class: 'col stability-col' }, out);
  }

  // ---------------------------------------------------------------- error against GPU time
  // Per case: every technique row's error (FLIP vs the reference; per ROI |ratio - 1|) against its
  // median GPU ms per frame, one colour per technique (the row's technique+label, as `sweep` names
  // its series; the same colour in every plot of the page), the Pareto front ringed and joined by
  // a step line. Suite level: per technique and preset, the medians over the cases it was plotted
  // in, and how often it is on a case's front. Plain SVG; every point has a <title> tooltip and
  // links to its row's card.
  var SERIES_COLOURS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf',
    '#bcbd22', '#7f7f7f'];
  var SERIES_SHAPES = ['circle', 'square', 'diamond', 'triangle'];  // the next shape once the colours run out
  var seriesStyle = {};  // technique (+label) -> { colour, shape }: built once from every row of the page

  function buildSeriesStyles(results) {
    var names = [];
    results.forEach(function (r) {
      if (r.kind !== 'negative_control' && names.indexOf(r.technique) < 0) names.push(r.technique);
    });
    names.sort();
    seriesStyle = {};
    names.forEach(function (name, i) {
      seriesStyle[name] = { colour: SERIES_COLOURS[i % SERIES_COLOURS.length],
        shape: SERIES_SHAPES[Math.floor(i / SERIES_COLOURS.length) % SERIES_SHAPES.length] };
    });
  }
  function styleOf(name) { return seriesStyle[name] || { colour: '#555', shape: 'circle' }; }

  // A marker of radius r centred on (x, y); 'offscale' is the up-pointing triangle drawn at the top
  // edge for an error above the axis (or not finite).
  function marker(shape, x, y, r, attrs) {
    var a = {};
    Object.keys(attrs || {}).forEach(function (k) { a[k] = attrs[k]; });
    function poly(pts) {
      a.d = 'M' + pts.map(function (p) { return (x + p[0] * r).toFixed(1) + ' ' + (y + p[1] * r).toFixed(1); }).join('L') + 'Z';
      return svgEl('path', a);
    }
    if (shape === 'square') return poly([[-0.85, -0.85], [0.85, -0.85], [0.85, 0.85], [-0.85, 0.85]]);
    if (shape === 'diamond') return poly([[0, -1.2], [1.2, 0], [0, 1.2], [-1.2, 0]]);
    if (shape === 'triangle') return poly([[-1.1, -0.8], [1.1, -0.8], [0, 1.1]]);
    if (shape === 'offscale') return poly([[-1, 0.9], [1, 0.9], [0, -1.1]]);
    a.cx = x.toFixed(1); a.cy = y.toFixed(1); a.r = r;
    return svgEl('circle', a);
  }
  function markerIcon(style, extra) {
    return svgEl('svg', { class: 'marker-icon', viewBox: '0 0 14 14', width: 14, height: 14 },
      [marker(style.shape, 7, 7, 4.5, extra || { fill: style.colour, stroke: '#fff', 'stroke-width': 1 })]);
  }

  function isReferenceRow(r) { return String(r.technique).split('+')[0] === 'reference'; }
  function rowName(r) { return r.technique + ' \u00b7 ' + r.preset; }
  function median(xs) {
    var s = xs.slice().sort(function (a, b) { return a - b; });
    var m = s.length >> 1;
    return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
  }

  // What a plot shows on y: the metric names it reads and the error of a row from them (NaN where a
  // metric is recorded as non-finite, i.e. null in results.js).
  function flipErrorSpec() {
    return { keys: ['flip_vs_reference'], title: 'FLIP vs reference',
      value: function (r) { var v = metric(r, 'flip_vs_reference'); return typeof v === 'number' ? v : NaN; } };
  }
  function roiKey(roi) { return 'roi_ratio_vs_reference_' + roi; }
  function roiErrorSpec(roi) {
    return { keys: [roiKey(roi)], title: 'ROI ' + roi + ' error',
      value: function (r) { var v = metric(r, roiKey(roi)); return typeof v === 'number' ? Math.abs(v - 1) : NaN; },
      ratio: function (r) { return metric(r, roiKey(roi)); } };
  }
  function worstRoiSpec(rois) {
    return { keys: rois.map(roiKey), title: 'worst ROI error',
      value: function (r) {
        var worst = -1;
        for (var i = 0; i < rois.length; ++i) {
          var v = metric(r, roiKey(rois[i]));
          if (typeof v !== 'number' || !isFinite(v)) return NaN;
          worst = Math.max(worst, Math.abs(v - 1));
        }
        return worst;
      },
      which: function (r) {  // the ROI that is worst, for the tooltip
        var best = null, worst = -1;
        rois.forEach(function (roi) {
          var v = metric(r, roiKey(roi));
          var e = typeof v === 'number' ? Math.abs(v - 1) : Infinity;
          if (e > worst) { worst = e; best = roi; }
        });
        return best;
      } };
  }

  // Why a technique row has no point in a plot of `spec`, or null when it has one.
  function missingReason(r, spec) {
    if (r.status === 'not_run') return 'not run';
    var m = r.metrics || {};
    for (var i = 0; i < spec.keys.length; ++i) {
      if (Object.prototype.hasOwnProperty.call(m, spec.keys[i])) continue;
      if (isReferenceRow(r)) return 'the reference itself';
      return r.status === 'error' ? 'error' : 'not compared with the reference';
    }
    if (!(typeof r.gpu_ms === 'number' && r.gpu_ms > 0)) return r.status === 'error' ? 'error' : 'no GPU time';
    return null;
  }

  // The technique rows of one case, split into points and rows left out (with why).
  function plotData(rows, spec) {
    var points = [], missing = [];
    rows.forEach(function (r) {
      if (r.kind === 'negative_control') return;
      var why = missingReason(r, spec);
      if (why) { missing.push({ row: r, why: why }); return; }
      points.push({ row: r, series: r.technique, x: r.gpu_ms, y: spec.value(r) });
    });
    markPareto(points);
    return { points: points, missing: missing, spec: spec };
  }

  // Pareto front: points no other point beats in both GPU time and error (ties in both: both stay).
  function markPareto(points) {
    var fin = points.filter(function (p) { return isFinite(p.y); });
    points.forEach(function (p) {
      p.pareto = isFinite(p.y) && !fin.some(function (q) {
        return q !== p && q.x <= p.x && q.y <= p.y && (q.x < p.x || q.y < p.y);
      });
    });
  }

  // ---- axes: linear from 0 with 1-2-5 steps, or log with 1-2-5 ticks
  function niceStep(raw) {
    var e = Math.pow(10, Math.floor(Math.log10(raw)));
    var m = raw / e;
    return (m <= 1 ? 1 : m <= 2 ? 2 : m <= 5 ? 5 : 10) * e;
  }
  function clean(v) { return parseFloat(v.toPrecision(12)); }
  function linearAxis(max) {
    var step = niceStep(max / 5);
    var top = clean(Math.ceil(max / step - 1e-9) * step);
    var ticks = [];
    for (var i = 0; i * step <= top * (1 + 1e-9); ++i) ticks.push(clean(i * step));
    return { lo: 0, hi: top, log: false, ticks: ticks };
  }
  function logAxis(min, max) {
    var all = [];
    for (var e = Math.floor(Math.log10(min)) - 1; e <= Math.ceil(Math.log10(max)) + 1; ++e) {
      [1, 2, 5].forEach(function (m) { all.push(clean(m * Math.pow(10, e))); });
    }
    var lo = all.filter(function (v) { return v <= min; }).pop();
    var hi = all.filter(function (v) { return v >= max; })[0];
    var ticks = all.filter(function (v) { return v >= lo && v <= hi; });
    if (ticks.length > 9) {  // wide ranges: the decades, and the ends where they are not crowded by one
      var decade = function (v) { var l = Math.log10(v); return Math.abs(l - Math.round(l)) < 1e-9; };
      var decades = ticks.filter(decade);
      ticks = ticks.filter(function (v, i) {
        if (decade(v)) return true;
        if (i !== 0 && i !== ticks.length - 1) return false;
        return decades.every(function (d) { return Math.abs(Math.log10(v / d)) > 0.45; });
      });
    }
    return { lo: lo, hi: hi, log: true, ticks: ticks };
  }
  // GPU time: log when the points span more than 10x, else linear from 0.
  function timeAxis(xs) {
    var min = Math.min.apply(null, xs), max = Math.max.apply(null, xs);
    return max / min > 10 ? logAxis(min, max) : linearAxis(max * 1.04);
  }
  // Error: linear from 0. Outliers (above 8x the upper quartile, with 3 points or more) are drawn
  // off scale at the top edge so that they do not squash the rest.
  function errorAxis(ys) {
    var fin = ys.filter(function (y) { return isFinite(y); }).sort(function (a, b) { return a - b; });
    var max = fin.length ? fin[fin.length - 1] : 0;
    if (fin.length >= 3) {
      var q = fin[Math.floor(0.75 * (fin.length - 1))];
      if (q > 0 && max > 8 * q) max = fin.filter(function (y) { return y <= 8 * q; }).pop();
    }
    return linearAxis(max > 0 ? max * 1.04 : 0.01);
  }
  function tickText(v) { return String(parseFloat(v.toPrecision(3))); }

  // One scatter. opts: points [{series, x, y, label, pareto, title, href}], xAxis, yAxis, xLabel,
  // yLabel, ariaLabel, joinSeries (a thin line through each series' points in x order).
  function scatterSvg(opts) {
    var W = 560, H = 340, L = 60, R = 18, T = 22, B = 46;
    var pw = W - L - R, ph = H - T - B, xa = opts.xAxis, ya = opts.yAxis;
    function X(v) {
      var f = xa.log ? (Math.log(v) - Math.log(xa.lo)) / (Math.log(xa.hi) - Math.log(xa.lo)) : (v - xa.lo) / (xa.hi - xa.lo);
      return L + pw * f;
    }
    function offScale(p) { return !isFinite(p.y) || p.y > ya.hi; }
    function Y(v) { return T + ph * (1 - Math.min(v, ya.hi) / ya.hi); }
    function PY(p) { return offScale(p) ? T - 9 : Y(p.y); }
    var kids = [svgEl('rect', { x: L, y: T, width: pw, height: ph, class: 'plot-area' })];
    xa.ticks.forEach(function (t) {
      kids.push(svgEl('line', { x1: X(t), x2: X(t), y1: T, y2: T + ph, class: 'grid' }));
      kids.push(svgEl('text', { x: X(t), y: T + ph + 15, 'text-anchor': 'middle', class: 'tick' }, [tickText(t)]));
    });
    ya.ticks.forEach(function (t) {
      kids.push(svgEl('line', { x1: L, x2: L + pw, y1: Y(t), y2: Y(t), class: 'grid' }));
      kids.push(svgEl('text', { x: L - 6, y: Y(t) + 4, 'text-anchor': 'end', class: 'tick' }, [tickText(t)]));
    });
    kids.push(svgEl('text', { x: L + pw / 2, y: H - 8, 'text-anchor': 'middle', class: 'axis-title' },
      [opts.xLabel + (xa.log ? ' (log scale)' : '')]));
    kids.push(svgEl('text', { x: 14, y: T + ph / 2, 'text-anchor': 'middle', class: 'axis-title',
      transform: 'rotate(-90 14 ' + (T + ph / 2) + ')' }, [opts.yLabel]));
    var above = opts.points.filter(function (p) { return isFinite(p.y) && p.y > ya.hi; }).length;
    var nonFinite = opts.points.filter(function (p) { return !isFinite(p.y); }).length;
    if (above + nonFinite) {
      kids.push(svgEl('text', { x: L + pw, y: T - 14, 'text-anchor': 'end', class: 'tick' }, ['\u25b2 ' +
        [above ? above + ' above ' + tickText(ya.hi) : '', nonFinite ? nonFinite + ' not finite' : ''].filter(Boolean).join(', ') +
        ' (at the top edge)']));
    }

    if (opts.joinSeries) {
      var bySeries = {};
      opts.points.forEach(function (p) { if (isFinite(p.y)) (bySeries[p.series] = bySeries[p.series] || []).push(p); });
      Object.keys(bySeries).forEach(function (name) {
        var ps = bySeries[name].sort(function (a, b) { return a.x - b.x; });
        if (ps.length < 2) return;
        kids.push(svgEl('polyline', { class: 'series-line', stroke: styleOf(name).colour,
          points: ps.map(function (p) { return X(p.x).toFixed(1) + ',' + PY(p).toFixed(1); }).join(' ') }));
      });
    }

    // The front as a staircase: right at the error of one point, then down to the next.
    var front = opts.points.filter(function (p) { return p.pareto; })
      .sort(function (a, b) { return a.x - b.x || a.y - b.y; });
    if (front.length) {
      var d = 'M' + X(front[0].x).toFixed(1) + ' ' + PY(front[0]).toFixed(1);
      for (var i = 1; i < front.length; ++i) d += 'H' + X(front[i].x).toFixed(1) + 'V' + PY(front[i]).toFixed(1);
      d += 'H' + (L + pw);  // nothing slower does better than the last front point
      kids.push(svgEl('path', { d: d, class: 'front-line' }));
    }

    // Points: the front drawn last, so that its rings are on top.
    var ordered = opts.points.filter(function (p) { return !p.pareto; }).concat(front);
    ordered.forEach(function (p) {
      var st = styleOf(p.series), x = X(p.x), y = PY(p);
      var g = [svgEl('title', null, [p.title])];
      if (p.pareto) g.push(svgEl('circle', { cx: x.toFixed(1), cy: y.toFixed(1), r: 9, class: 'front-ring' }));
      g.push(marker(offScale(p) ? 'offscale' : st.shape, x, y, 5, { fill: st.colour, class: 'pt' }));
      kids.push(p.href ? svgEl('a', { href: p.href, class: 'pt-link' }, g) : svgEl('g', null, g));
    });

    // Labels: the front always, every point while there are few. Each takes the first of four
    // places around its point that stays inside the plot and clear of the labels placed and the
    // markers; a front point tries below-left first, where no point can be (nothing is both
    // faster and better). A label with no free place is left out (the tooltip still has it).
    var obstacles = ordered.map(function (p) {
      var x = X(p.x), y = PY(p);
      return { x0: x - 6, x1: x + 6, y0: y - 6, y1: y + 6 };
    });
    var labelAll = opts.points.length <= 14;
    function hits(b) {
      return obstacles.some(function (o) { return o.x0 < b.x1 && b.x0 < o.x1 && o.y0 < b.y1 && b.y0 < o.y1; });
    }
    // Front points first, so that they get the best places.
    front.concat(ordered.filter(function (p) { return !p.pareto; })).forEach(function (p) {
      if (!p.label || !(labelAll || p.pareto || offScale(p))) return;
      var text = offScale(p) ? p.label + ' ' + (isFinite(p.y) ? tickText(p.y) : '\u221e') : p.label;
      var px = X(p.x), py = PY(p), w = text.length * 6.1 + 2;
      var places = [
        { left: true, dy: 16 }, { left: false, dy: 16 }, { left: false, dy: -8 }, { left: true, dy: -8 }
      ];
      if (!p.pareto) places = [places[2], places[3], places[1], places[0]];
      for (var i = 0; i < places.length; ++i) {
        var pl = places[i];
        var x = pl.left ? px - 9 : px + 9, y = py + pl.dy;
        var box = { x0: pl.left ? x - w : x, x1: pl.left ? x : x + w, y0: y - 9, y1: y + 2 };
        if (box.x0 < L + 2 || box.x1 > L + pw + R - 2 || box.y0 < T - 2 || box.y1 > T + ph - 1) continue;
        if (hits(box)) continue;
        obstacles.push(box);
        kids.push(svgEl('text', { x: x.toFixed(1), y: y.toFixed(1), 'text-anchor': pl.left ? 'end' : 'start',
          class: 'pt-label' + (p.pareto ? ' on-front' : '') }, [text]));
        return;
      }
    });
    return svgEl('svg', { class: 'scatter', viewBox: '0 0 ' + W + ' ' + H, role: 'img', 'aria-label': opts.ariaLabel }, kids);
  }

  // A point's label: its preset where its technique has several points in the plot (the colour
  // tells the technique), else the technique.
  function labelPoints(points, presetOf, suffix) {
    var count = {};
    points.forEach(function (p) { count[p.series] = (count[p.series] || 0) + 1; });
    points.forEach(function (p) { p.label = (count[p.series] > 1 ? presetOf(p) : p.series) + (suffix ? suffix(p) : ''); });
  }

  // The tooltip of one case row's point.
  function pointTitle(p, spec, c) {
    var r = p.row;
    var lines = [rowName(r) + (r.status && r.status !== 'pass' ? '  [' + r.status.replace('_', ' ') + ']' : '')];
    if (optionsText(r.options)) lines.push(optionsText(r.options));
    var yv = isFinite(p.y) ? fmtNum(p.y, 4) : 'not finite';
    if (spec.which && isFinite(p.y)) yv += ' (ROI ' + spec.which(r) + ')';
    if (spec.ratio && isFinite(p.y)) yv += ' (ratio ' + fmtNum(spec.ratio(r), 4) + ')';
    lines.push('GPU ' + fmtMs(r.gpu_ms) + ' ms/frame \u00b7 ' + spec.title + ' ' + yv);
    if (spec.keys[0] !== 'flip_vs_reference' && typeof metric(r, 'flip_vs_reference') === 'number') {
      lines.push('FLIP vs reference ' + fmtNum(metric(r, 'flip_vs_reference'), 4));
    }
    if (typeof r.wall_s === 'number') lines.push('wall clock ' + fmtNum(r.wall_s, 1) + ' s');
    if (p.pareto) lines.push('on the Pareto front');
    if (c) lines.push('click: the row\'s images');
    return lines.join('\n');
  }

  // "2 not run (a · high, b · low), 1 not compared with the reference (c · medium)"
  function missingText(missing) {
    var order = [], by = {};
    missing.forEach(function (m) {
      if (!by[m.why]) { by[m.why] = []; order.push(m.why); }
      by[m.why].push(rowName(m.row));
    });
    return order.map(function (why) {
      var names = by[why];
      var shown = names.slice(0, 4).join(', ') + (names.length > 4 ? ' and ' + (names.length - 4) + ' more' : '');
      return names.length + ' ' + why + ' (' + shown + ')';
    }).join('; ');
  }

  function seriesLegend(names, extra) {
    return h('div', { class: 'series-legend' }, names.map(function (n) {
      return h('span', { class: 'series-key' }, [markerIcon(styleOf(n)), n]);
    }).concat(extra || []));
  }
  function frontKey() {
    return h('span', { class: 'series-key front-key' }, [
      svgEl('svg', { class: 'marker-icon', viewBox: '0 0 40 18', width: 40, height: 18 }, [
        svgEl('path', { d: 'M13 5H28V14H40', class: 'front-line' }),
        svgEl('circle', { cx: 7, cy: 5, r: 2.5, fill: '#1d2330' }),
        svgEl('circle', { cx: 7, cy: 5, r: 4.5, class: 'front-ring' })]),
      'Pareto front']);
  }

  // One plot with its caption, for the rows of one case and one error spec.
  function caseScatterFigure(data, c, indexOf, title, note) {
    var techCount = data.points.length + data.missing.length;
    var pts = data.points.map(function (p) {
      return { series: p.series, x: p.x, y: p.y, pareto: p.pareto, row: p.row,
        href: '#' + rowAnchor(p.row, indexOf(p.row)) };
    });
    labelPoints(pts, function (p) { return p.row.preset; });
    pts.forEach(function (p) { p.title = pointTitle(p, data.spec, c); });
    var fig = [title];
    if (pts.length) {
      fig.push(scatterSvg({ points: pts, xAxis: timeAxis(pts.map(function (p) { return p.x; })),
        yAxis: errorAxis(pts.map(function (p) { return p.y; })), xLabel: 'GPU ms per frame (median)',
        yLabel: data.spec.title + ' (lower is better)', ariaLabel: data.spec.title + ' against GPU time' }));
    } else {
      fig.push(h('div', { class: 'scatter-empty' }, 'No row to plot.'));
    }
    var onFront = pts.filter(function (p) { return p.pareto; }).map(function (p) { return rowName(p.row); });
    fig.push(h('figcaption', null, [
      note, ' ', h('b', null, pts.length + ' of ' + techCount + ' technique row' + (techCount === 1 ? '' : 's') + ' plotted'),
      '.', onFront.length > 6 ? ' Pareto front (ringed, step line): ' + onFront.length + ' rows.'
        : onFront.length ? ' Pareto front (ringed, step line): ' + onFront.join(', ') + '.' : '',
      data.missing.length ? [' ', h('span', { class: 'not-plotted' }, 'Not plotted: ' + missingText(data.missing) + '.')] : ''
    ]));
    return fig;
  }

  // The case's plots: FLIP vs reference and, where the case has ROIs, the ROI error of one ROI at a
  // time (a picker: the case's ROIs and the worst of them).
  function caseScatter(c, rows, indexOf) {
    var tech = rows.filter(function (r) { return r.kind !== 'negative_control'; });
    if (!tech.length) return null;
    var flipSpec = flipErrorSpec();
    var rois = ((c && c.rois) || []).map(function (r) { return r.name; });
    var roiSpecs = rois.map(roiErrorSpec);
    var withRoi = rois.length > 0 && tech.some(function (r) { return !missingReason(r, roiSpecs[0]); });
    var names = [];
    tech.forEach(function (r) {
      var shown = !missingReason(r, flipSpec) || (withRoi && roiSpecs.some(function (sp) { return !missingReason(r, sp); }));
      if (shown && names.indexOf(r.technique) < 0) names.push(r.technique);
    });
    names.sort();

    var flip = plotData(tech, flipSpec);
    if (!flip.points.length && !withRoi) {  // e.g. a variant-only case, or a profile that ran none of it
      return h('p', { class: 'scatter-none' }, [h('b', null, 'Error against GPU time: '),
        'no row to plot. ' + missingText(flip.missing) + '.']);
    }
    var figures = [h('figure', { class: 'scatter-fig' }, caseScatterFigure(flip, c, indexOf,
      h('div', { class: 'fig-title' }, 'FLIP vs reference'),
      'y: mean FLIP vs the path-traced reference (vs the analytic image in a case without one); x: median GPU time ' +
      'per frame; one point per technique row.'))];
    if (withRoi) figures.push(roiScatter(c, tech, rois, roiSpecs, indexOf));
    return h('div', { class: 'scatter-block' }, [
      h('h3', null, 'Error against GPU time'),
      seriesLegend(names, [frontKey()]),
      h('div', { class: 'scatter-figs' }, figures)
    ]);
  }

  function roiScatter(c, tech, rois, roiSpecs, indexOf) {
    var choices = rois.map(function (roi, i) {
      return { label: roi, spec: roiSpecs[i], what: 'ROI ' + roi };
    });
    if (rois.length > 1) {
      choices.push({ label: 'worst', spec: worstRoiSpec(rois),
        what: 'each of the case\u2019s ' + rois.length + ' ROIs (the worst per row)' });
    }
    var fig = h('figure', { class: 'scatter-fig' });
    var buttons = choices.map(function (ch, i) {
      return h('button', { type: 'button', title: ch.spec.title, onclick: function () { show(i); } }, ch.label);
    });
    var picker = h('div', { class: 'fig-title roi-picker' }, [h('span', null, 'ROI error')].concat(buttons));
    function show(i) {
      buttons.forEach(function (b, j) { b.classList.toggle('active', i === j); });
      fig.textContent = '';
      append(fig, caseScatterFigure(plotData(tech, choices[i].spec), c, indexOf, picker,
        'y: |ratio \u2212 1|, the ratio being the mean luminance in ' + choices[i].what +
        ' over the reference\u2019s (0: it matches); x: median GPU time per frame.'));
    }
    show(0);
    return fig;
  }

  // ---- suite level: one point per technique and preset, medians over the cases
  function suiteScatter(caseRows) {
    var groups = {}, keys = [];
    caseRows.forEach(function (cr) {
      var data = plotData(cr.rows, flipErrorSpec());
      data.points.forEach(function (p) {
        if (!isFinite(p.y)) return;
        var k = p.row.technique + '\u0000' + p.row.preset;
        if (!groups[k]) {
          groups[k] = { technique: p.row.technique, preset: p.row.preset, cases: [], ms: [], flip: [], front: 0 };
          keys.push(k);
        }
        var g = groups[k];
        g.cases.push(cr.name); g.ms.push(p.x); g.flip.push(p.y);
        if (p.pareto) g.front++;
      });
    });
    if (!keys.length) return null;
    var caseCount = caseRows.filter(function (cr) {
      return keys.some(function (k) { return groups[k].cases.indexOf(cr.name) >= 0; });
    }).length;
    var pts = keys.map(function (k) {
      var g = groups[k];
      return { series: g.technique, x: median(g.ms), y: median(g.flip), g: g };
    });
    labelPoints(pts, function (p) { return p.g.preset; },
      function (p) { return p.g.cases.length < caseCount ? ' (' + p.g.cases.length + ')' : ''; });
    markPareto(pts);
    pts.forEach(function (p) {
      var g = p.g;
      p.title = g.technique + ' \u00b7 ' + g.preset + '\nmedian over ' + g.cases.length + ' case' + (g.cases.length === 1 ? '' : 's') +
        ': GPU ' + fmtMs(p.x) + ' ms/frame \u00b7 FLIP vs reference ' + fmtNum(p.y, 4) +
        '\non its case\u2019s Pareto front in ' + g.front + ' of them: ' + g.cases.join(', ') +
        (p.pareto ? '\non the front of these medians' : '');
    });
    var names = [];
    pts.forEach(function (p) { if (names.indexOf(p.series) < 0) names.push(p.series); });
    names.sort();
    var svg = scatterSvg({ points: pts, xAxis: timeAxis(pts.map(function (p) { return p.x; })),
      yAxis: errorAxis(pts.map(function (p) { return p.y; })), xLabel: 'median GPU ms per frame over its cases',
      yLabel: 'median FLIP vs reference', ariaLabel: 'per technique: median FLIP against median GPU time', joinSeries: true });

    // The table ranks by how often a technique/preset is on its case's front: like-for-like, unlike
    // the medians of different case sets.
    var ranked = pts.slice().sort(function (a, b) {
      return (b.g.front / b.g.cases.length - a.g.front / a.g.cases.length) || (a.y - b.y) || (a.x - b.x);
    });
    var table = h('table', { class: 'results suite-rank' }, [
      h('thead', null, h('tr', null, [
        h('th', null, 'technique'), h('th', null, 'preset'),
        h('th', { class: 'num', title: 'cases where this technique and preset has a plotted point' }, 'cases'),
        h('th', { class: 'num' }, 'median ms'), h('th', { class: 'num' }, 'median FLIP'),
        h('th', { class: 'num', title: 'cases where no other row of the case is both faster and lower-error' }, 'on front')
      ])),
      h('tbody', null, ranked.map(function (p) {
        return h('tr', null, [
          h('td', null, [markerIcon(styleOf(p.series)), ' ', p.g.technique]),
          h('td', null, p.g.preset),
          h('td', { class: 'num', title: p.g.cases.join(', ') }, String(p.g.cases.length)),
          h('td', { class: 'num' }, fmtMs(p.x)),
          h('td', { class: 'num' }, fmtNum(p.y, 4)),
          h('td', { class: 'num' }, p.g.front + ' / ' + p.g.cases.length)
        ]);
      }))
    ]);
    return h('section', { class: 'suite-scatter' }, [
      h('h2', null, 'Error against GPU time, per technique'),
      seriesLegend(names, [frontKey()]),
      h('div', { class: 'suite-scatter-body' }, [
        h('figure', { class: 'scatter-fig' }, [svg, h('figcaption', null, [
          'One point per technique and preset: the ', h('b', null, 'median over the cases'), ' it was plotted in ' +
          '(of ' + caseCount + ' case' + (caseCount === 1 ? '' : 's') + '; the count in brackets where fewer) ' +
          'of its mean FLIP against the reference ' +
          '(y) and its median GPU ms per frame (x). Lines join one technique\u2019s presets; ringed: no other point has both ' +
          'medians lower. Cases differ in resolution and content, so medians over different case sets are not like-for-like: ' +
          'the table counts how often each row is on its own case\u2019s front, and the per-case plots below compare ' +
          'rows of one scene.'
        ])]),
        h('div', { class: 'suite-rank-wrap' }, [
          h('div', { class: 'fig-title' }, 'Ranked by how often it is on its case\u2019s Pareto front'), table])
      ])
    ]);
  }

  // ---------------------------------------------------------------- per row detail card
  function detailCard(row, idx, c, cs, maxMs) {
    var neg = row.kind === 'negative_control';
    var title = neg ? [h('span', { class: 'neg-name' }, row.negative_control || 'negative control'), ' ',
      h('span', { class: 'sub' }, row.technique + ' \u00b7 ' + row.preset)]
      : [row.technique, ' ', h('span', { class: 'sub' }, row.preset)];
    var opts = optionsText(row.options);
    var msgs = row.messages || [];
    // A row that did not run has no images, checks or timings: its card is the header and its message.
    var notRun = row.status === 'not_run';
    var head = h('header', { class: 'card-head' }, [
      badge(row),
      h('h4', null, title),
      opts ? h('span', { class: 'opts' }, opts) : null,
      h('span', { class: 'spacer' }),
      notRun ? null : h('span', { class: 'kv' }, ['FLIP ', h('b', null, fmtNum(metric(row, 'flip_vs_reference'), 4))]),
      notRun ? null : h('span', { class: 'kv' }, ['PSNR ', h('b', null, fmtNum(metric(row, 'psnr_vs_reference'), 2)), ' dB']),
      notRun ? null : h('span', { class: 'kv' }, ['GPU ', h('b', null, fmtMs(row.gpu_ms)), ' ms']),
      otherClassTag(row)
    ]);
    if (notRun) {
      return h('article', { class: 'card not_run' + (neg ? ' negative' : ''), id: rowAnchor(row, idx) }, [
        head,
        h('ul', { class: 'messages not-run' }, (msgs.length ? msgs : ['not run by this profile'])
          .map(function (m) { return h('li', null, m); }))
      ]);
    }
    return h('article', { class: 'card ' + (row.status || 'error') + (neg ? ' negative' : ''), id: rowAnchor(row, idx) }, [
      head,
      neg ? h('p', { class: 'why' }, [h('b', null, 'Breaks: '), row.why || '(no description)']) : null,
      msgs.length ? h('ul', { class: 'messages ' + (row.status === 'pass' ? 'ok' : 'bad') },
        msgs.map(function (m) { return h('li', null, m); })) : null,
      imageRow(row, c, cs),
      (row.printouts || []).length ? h('div', { class: 'printouts' }, row.printouts.map(function (p) {
        return h('details', null, [h('summary', null, 'printout: ' + p.name), h('pre', { class: 'printout' }, p.text)]);
      })) : null,
      attributionSection(row),
      h('div', { class: 'card-cols' }, [
        h('section', { class: 'col' }, [h('h5', null, 'Checks'), checksList(row)]),
        h('section', { class: 'col' }, [h('h5', null, 'GPU passes & plan')].concat(passBars(row, maxMs))),
        stabilitySection(row)
      ])
    ]);
  }

  // Error attribution of a row its case flags (gibench run --attribute): the largest stage's share
  // per ROI and a link to the waterfall page; asked for but not run, or failed, said so.
  function attributionSection(row) {
    var a = row.attribution;
    if (!a) return null;
    if (a.not_run) return h('p', { class: 'attribution not-run' }, [h('b', null, 'Error attribution: '), 'not run: ' + a.not_run]);
    if (a.error) return h('p', { class: 'attribution bad' }, [h('b', null, 'Error attribution failed: '), a.error]);
    var items = (a.rois || []).map(function (r) {
      return h('li', null, [h('b', null, r.roi), ': largest share ' + r.largest + ' (MSE ' + fmtNum(r.mse) +
        ', energy ' + (r.signed_energy >= 0 ? '+' : '') + fmtNum(100 * r.signed_energy, 1) + '%, oracle floor ' +
        fmtNum(r.oracle_floor) + ')']);
    });
    return h('section', { class: 'attribution' }, [
      h('h5', null, ['Error attribution (stages in the game: ' + (a.stages_in_game || []).join(', ') + '; ' + a.renders +
        ' renders) ', h('a', { href: a.page }, 'waterfall')]),
      h('ul', null, items)
    ]);
  }

  // A row compared with another device class's golden (this device has none approved): amber,
  // never silent.
  function otherClassTag(row) {
    var dev = (window.GIB_RESULTS && window.GIB_RESULTS.device) || {};
    var want = dev.golden_class || dev['class'];
    if (!row.golden_class || !want || row.golden_class === want) return null;
    return h('div', { class: 'golden-other-class', title: 'no ' + want + ' golden is approved: compared with the ' +
      row.golden_class + ' one' }, row.golden_class + ' golden');
  }

  // ---------------------------------------------------------------- per case
  function resultsTable(rows, indexOf) {
    var psnrDef = (window.GIB_RESULTS && window.GIB_RESULTS.psnr_definition) || '';
    return h('table', { class: 'results' }, [
      h('thead', null, h('tr', null, [
        h('th', null, 'technique'), h('th', null, 'preset'), h('th', null, 'status'),
        h('th', { class: 'num', title: 'mean FLIP vs the path-traced reference (lower is better)' }, 'FLIP ref'),
        h('th', { class: 'num', title: psnrDef }, 'PSNR ref'),
        h('th', { class: 'num', title: 'mean FLIP vs the approved golden' }, 'FLIP golden'),
        h('th', { class: 'num' }, 'GPU ms'),
        h('th', null, 'messages')
      ])),
      h('tbody', null, rows.map(function (r) {
        var neg = r.kind === 'negative_control';
        var msgs = r.messages || [];
        var anchor = '#' + rowAnchor(r, indexOf(r));
        return h('tr', { class: 'st-' + (r.status || 'error') }, [
          h('td', null, [h('a', { href: anchor }, neg ? (r.negative_control || r.technique) : r.technique),
            neg ? h('div', { class: 'sub' }, r.technique) : null,
            optionsText(r.options) ? h('div', { class: 'sub' }, optionsText(r.options)) : null]),
          h('td', null, r.preset),
          h('td', null, badge(r)),
          h('td', { class: 'num' }, fmtNum(metric(r, 'flip_vs_reference'), 4)),
          h('td', { class: 'num' }, fmtNum(metric(r, 'psnr_vs_reference'), 2)),
          h('td', { class: 'num' }, [fmtNum(metric(r, 'flip_vs_golden'), 4), otherClassTag(r)]),
          h('td', { class: 'num' }, fmtMs(r.gpu_ms)),
          h('td', { class: 'msgs' }, msgs.length ? msgs.map(function (m) { return h('div', null, m); }) : h('span', { class: 'muted' }, '\u2014'))
        ]);
      }))
    ]);
  }

  function countStatus(rows) {
    var n = { pass: 0, fail: 0, error: 0, known_failure: 0, skipped: 0, not_run: 0 };
    rows.forEach(function (r) { n[r.status in n ? r.status : 'error']++; });
    return n;
  }

  function caseSection(name, c, rows, errors, indexOf) {
    var cs = { ev: 0, canvases: [] };
    var tech = rows.filter(function (r) { return r.kind !== 'negative_control'; });
    var neg = rows.filter(function (r) { return r.kind === 'negative_control'; });
    var n = countStatus(rows);
    var bad = n.fail + n.error + errors.length;
    var maxMs = 0;
    rows.forEach(function (r) {
      (r.passes || []).forEach(function (p) {
        if (p.status === 'ran') maxMs = Math.max(maxMs, typeof p.max_ms === 'number' ? p.max_ms : 0, typeof p.ms === 'number' ? p.ms : 0);
      });
    });

    var evLabel = h('output', { class: 'ev-val' }, '+0.0 EV');
    function setEv(v) {
      cs.ev = v;
      evLabel.textContent = (v >= 0 ? '+' : '\u2212') + Math.abs(v).toFixed(1) + ' EV';
      cs.canvases.forEach(function (k) { drawFloat(k.canvas, k.img, v); });
    }
    var slider = h('input', { type: 'range', min: -8, max: 8, step: 0.25, value: 0, 'aria-label': 'exposure (EV)',
      oninput: function (e) { setEv(parseFloat(e.target.value)); } });
    var reset = h('button', { type: 'button', onclick: function () { slider.value = 0; setEv(0); } }, 'reset');

    var meta = [];
    if (c) {
      meta.push(h('span', null, c.width + '\u00d7' + c.height));
      meta.push(h('span', null, ['compares ', h('code', null, c.output)]));
      if (c.rois && c.rois.length) meta.push(h('span', null, 'ROIs: ' + c.rois.map(function (r) { return r.name; }).join(', ')));
    }
    meta.push(h('span', null, tech.length + ' technique row' + (tech.length === 1 ? '' : 's') + ', ' + neg.length + ' negative control' + (neg.length === 1 ? '' : 's') +
      (n.not_run ? ' (' + n.not_run + ' not run)' : '')));

    var idx = function (r) { return indexOf(r); };
    var nothingRan = rows.length > 0 && n.not_run === rows.length;  // grey, not green: nothing passed
    var section = h('section', { class: 'case ' + (bad ? 'has-fail' : nothingRan ? 'not-run' : 'all-pass'), id: 'case-' + slug(name) }, [
      h('header', { class: 'case-head' }, [
        h('h2', null, name),
        nothingRan ? null : h('span', { class: 'pill pass' }, n.pass + ' passed'),
        n.fail ? h('span', { class: 'pill fail' }, n.fail + ' failed') : null,
        n.known_failure ? h('span', { class: 'pill known_failure' }, n.known_failure + ' known failure') : null,
        n.skipped ? h('span', { class: 'pill skipped', title: 'negative controls whose thresholds need the stability scan (--no-stability-scan)' }, n.skipped + ' skipped') : null,
        n.not_run ? h('span', { class: 'pill not_run', title: 'rows this run\'s profile did not run: not counted as passed' }, n.not_run + ' not run') : null,
        n.error + errors.length ? h('span', { class: 'pill error' }, (n.error + errors.length) + ' error' + (n.error + errors.length === 1 ? '' : 's')) : null
      ]),
      c && c.description ? h('p', { class: 'desc' }, c.description) : null,
      h('div', { class: 'meta' }, meta),
      errors.length ? h('div', { class: 'case-errors' }, errors.map(function (e) { return h('div', null, [h('b', null, 'case error: '), e]); })) : null,
      tech.length ? resultsTable(tech, idx) : null,
      caseScatter(c, rows, idx),
      h('div', { class: 'exposure' }, [h('label', null, 'Exposure'), h('span', { class: 'ev-min' }, '\u22128'), slider,
        h('span', { class: 'ev-max' }, '+8'), evLabel, reset,
        h('span', { class: 'hint' }, 'applies to reference and outputs of this case (HDR panels)')]),
      h('div', { class: 'cards' }, tech.map(function (r) { return detailCard(r, idx(r), c, cs, maxMs); })),
      neg.length ? h('section', { class: 'negatives' }, [
        h('h3', null, 'Negative controls'),
        h('p', { class: 'explain' }, 'Each one deliberately breaks the technique. It must fail at least one threshold: ' +
          '\u201ccaught\u201d means the case can tell good from bad; \u201cNOT caught\u201d fails the case.'),
        resultsTable(neg, idx),
        h('div', { class: 'cards' }, neg.map(function (r) { return detailCard(r, idx(r), c, cs, maxMs); }))
      ]) : null
    ]);
    return { el: section, n: n, bad: bad, nothingRan: nothingRan };
  }

  // ---------------------------------------------------------------- page
  function verdictText(failed, total) {
    if (failed) return failed + ' failed';
    if (total.not_run && !total.pass && !total.known_failure) return 'nothing ran (' + total.not_run + ' not run)';
    var notes = [];
    if (total.known_failure) notes.push(total.known_failure + ' known failure' + (total.known_failure === 1 ? '' : 's'));
    if (total.not_run) notes.push(total.not_run + ' not run');
    return notes.length ? 'passed (' + notes.join(', ') + ')' : 'all passed';
  }

  function render() {
    var R = window.GIB_RESULTS;
    var app = document.getElementById('app');
    app.textContent = '';
    if (!R || typeof R !== 'object') {
      fail('results.js did not load (window.GIB_RESULTS is missing)');
      app.appendChild(h('p', { class: 'fatal' }, 'results.js did not load: no results to show.'));
      return;
    }
    var results = R.results || [];
    var cases = R.cases || [];
    var caseErrors = R.case_errors || [];
    var dev = R.device || {};

    // Case order: the cases list, then any case named only by a row.
    var order = [], byName = {};
    cases.forEach(function (c) { if (!byName[c.name]) { byName[c.name] = c; order.push(c.name); } });
    results.forEach(function (r) { if (!(r.case in byName)) { byName[r.case] = null; order.push(r.case); } });
    var errorsFor = {};  // case errors not naming a case (e.g. validation) appear only in the top box
    caseErrors.forEach(function (e) {
      var hit = order.filter(function (n) { return e.indexOf(n + ':') === 0; })[0];
      if (hit !== undefined) (errorsFor[hit] = errorsFor[hit] || []).push(e.slice(hit.length + 1).trim());
    });
    var indexOf = function (r) { return results.indexOf(r); };

    var total = countStatus(results);
    var failed = total.fail + total.error + caseErrors.length;

    document.title = (failed ? '\u2717 ' + failed + ' failed' : '\u2713 all passed') + ' \u2014 gibench report';

    buildSeriesStyles(results);
    var sections = order.map(function (name) {
      var rows = results.filter(function (r) { return r.case === name; });
      return { name: name, s: caseSection(name, byName[name], rows, errorsFor[name] || [], indexOf) };
    });

    var header = h('header', { class: 'top ' + (failed ? 'bad' : 'good') }, [
      h('div', { class: 'top-inner' }, [
        h('div', { class: 'brand' }, [h('h1', null, 'gibench'), h('span', { class: 'verdict' }, verdictText(failed, total))]),
        h('div', { class: 'device' }, [
          h('div', { class: 'dev-name' }, dev.name || 'unknown device'),
          h('div', { class: 'dev-sub' }, [dev.type, dev.driver, dev.driver_info].filter(Boolean).join(' \u00b7 ') +
            (dev['class'] ? ' \u00b7 device class ' + dev['class'] : '') +
            (dev.golden_class || dev['class'] ? ' \u00b7 golden class ' + (dev.golden_class || dev['class']) : '') +
            (dev.tier ? ' \u00b7 tier ' + dev.tier : '')),
          R.merged ? h('div', { class: 'dev-sub', title: (R.merged.devices || []).map(function (d) {
            return 'shard ' + d.shard + ': ' + d.name; }).join('\n') }, 'merged from ' + R.merged.shards + ' shards') : null,
          R.shard ? h('div', { class: 'dev-sub' }, 'shard ' + R.shard.index + '/' + R.shard.count + ': ' +
            (R.shard.rows || []).length + ' of ' + (R.shard.plan || []).length + ' rows') : null
        ]),
        h('div', { class: 'totals' }, [
          h('div', { class: 'total pass' }, [h('b', null, String(total.pass)), h('span', null, 'passed')]),
          h('div', { class: 'total fail' + (total.fail ? '' : ' zero') }, [h('b', null, String(total.fail)), h('span', null, 'failed')]),
          h('div', { class: 'total error' + (total.error + caseErrors.length ? '' : ' zero') }, [h('b', null, String(total.error + caseErrors.length)), h('span', null, 'errors')]),
          total.known_failure ? h('div', { class: 'total known_failure', title: 'runs marked known_failure in their case: reported, not counted' },
            [h('b', null, String(total.known_failure)), h('span', null, 'known')]) : null,
          total.not_run ? h('div', { class: 'total not_run', title: 'rows this run\'s profile did not run: not counted as passed' },
            [h('b', null, String(total.not_run)), h('span', null, 'not run')]) : null
        ])
      ])
    ]);

    var errorBox = caseErrors.length ? h('section', { class: 'errors-box' }, [
      h('h2', null, caseErrors.length + ' case error' + (caseErrors.length === 1 ? '' : 's')),
      h('ul', null, caseErrors.map(function (e) { return h('li', null, e); }))
    ]) : null;

    var nav = h('nav', { class: 'case-nav' }, sections.map(function (x) {
      var n = x.s.n;
      return h('a', { href: '#case-' + slug(x.name), class: x.s.bad ? 'bad' : x.s.nothingRan ? 'not-run' : 'good' }, [
        h('span', { class: 'dot' }), x.name,
        h('span', { class: 'count' }, n.pass + '/' + (n.pass + n.fail + n.error))
      ]);
    }));

    var roiToggle = h('input', { type: 'checkbox', checked: true, onchange: function (e) {
      document.body.classList.toggle('hide-rois', !e.target.checked);
    } });
    var failToggle = h('input', { type: 'checkbox', onchange: function (e) {
      document.body.classList.toggle('only-failures', e.target.checked);
    } });
    var toolbar = h('div', { class: 'toolbar' }, [
      h('label', null, [roiToggle, ' ROI outlines']),
      h('label', null, [failToggle, ' only failures']),
      h('span', { class: 'spacer' }),
      h('span', { class: 'hint' }, 'Hover an image for pixel values; click a technique to jump to its images.')
    ]);

    var suite = suiteScatter(order.map(function (name) {
      return { name: name, rows: results.filter(function (r) { return r.case === name; }) };
    }));
    var main = h('main', null, [errorBox, nav, toolbar, suite].concat(sections.map(function (x) { return x.s.el; })).concat([
      !order.length ? h('p', { class: 'muted' }, 'No cases ran.') : null,
      h('footer', null, [
        R.psnr_definition ? h('p', null, [h('b', null, 'PSNR: '), R.psnr_definition]) : null,
        h('p', null, 'FLIP error maps use the magma colour map (black = no error, light yellow = 1). ' +
          'Negative-control status pass means the break was caught. NaN pixels show in magenta.')
      ])
    ]));
    app.appendChild(header);
    app.appendChild(main);
  }

  function start() {
    (window.GIB_ERRORS || []).forEach(fail);
    try {
      render();
    } catch (e) {
      console.error(e && e.stack ? e.stack : e);
      fail('render: ' + (e && e.message ? e.message : String(e)));
    }
    // Canvases are drawn synchronously above; the images' load events all come before the
    // window's load event, which headless Chromium waits for before it dumps the DOM.
    Promise.all(pendingImages).then(function () {
      if (failedWith === null) document.body.dataset.gibStatus = 'ok';
    });
  }

  start();
})();
