// The JavaScript side of the FScript oracle (tests/oracle/js_oracle.cpp): what the generated
// programs need beyond plain JavaScript, and the loop that runs them. Each helper says why it
// exists; docs/language.md ("Departures from JavaScript") lists the language's own choices.

// FScript computes in float32: every arithmetic result is rounded once to float. For + - * / and
// sqrt, double then float is the correctly rounded float result (double has more than 2p + 2 bits).
const __f = Math.fround;
const __pi = Math.fround(Math.PI);

// Departure: min and max of two equal operands return the first (min(-0, 0) is -0, min(0, -0) is
// +0), where Math.min and Math.max order -0 below +0. So they are two selects, which every
// backend's SIMD code does in two instructions. NaN wins, as in JavaScript.
function __min(a, b) { return b !== b ? b : (b < a ? b : a); }
function __max(a, b) { return b !== b ? b : (b > a ? b : a); }
// Addition: clamp(x, lo, hi) is min(max(x, lo), hi); Math has no clamp.
function __clamp(x, lo, hi) { return __min(__max(x, lo), hi); }

// Departure: an index is rounded like Math.round (a[1.6] is a[2]), and one outside the array is a
// runtime error, where JavaScript reads undefined.
function __idx(a, i) {
  const r = Math.round(i);
  if (!(r >= 0) || r >= a.length) throw new Error('index out of range');
  return r;
}
// new Array(n) starts filled with 0, not with holes (FScript has no undefined).
function __new_array(n) { return new Array(n).fill(0); }

// Runs every program on its points and prints one line per program: per point the result's
// float32 bits in hex, or E (a runtime error the language defines: an index, an array used
// before it is created), X:name (any other exception), D (a number that is not a float: a
// missing rounding), T (not a number at all).
function __run(programs) {
  const view = new DataView(new ArrayBuffer(4));
  const bits = (h) => { view.setUint32(0, parseInt(h, 16)); return view.getFloat32(0); };
  const lines = [];
  for (const [fn, points] of programs) {
    const out = [];
    for (let p = 0; p < points.length; p += 4) {
      let r;
      try {
        r = fn(bits(points[p]), bits(points[p + 1]), bits(points[p + 2]), bits(points[p + 3]));
      } catch (e) {
        const defined = e.message === 'index out of range' || (e instanceof TypeError && /null/.test(e.message));
        out.push(defined ? 'E' : 'X:' + e.name);
        continue;
      }
      if (typeof r !== 'number') { out.push('T'); continue; }
      if (r === r && Math.fround(r) !== r) { out.push('D'); continue; }
      view.setFloat32(0, r);
      out.push(view.getUint32(0).toString(16).padStart(8, '0'));
    }
    lines.push(out.join(' '));
  }
  process.stdout.write(lines.join('\n') + '\n');
}
