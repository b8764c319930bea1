// A call on a BaseMesh or Evaluator after its free(): wasm-bindgen's glue passes the freed
// object's pointer (0) to Rust, whose bindings throw "null pointer passed to rust". That is
// true but names neither the object nor the way out, so every method and getter of the two
// classes checks first and says both. The module instance is unharmed either way: this only
// changes the message. Imported for its side effect by the package's entries (auto.js, node.js,
// init.js); the prototypes are shared, so patching once covers every entry.
import { BaseMesh, Evaluator } from './subsurf.js';

const REMEDIES = [
  [BaseMesh, 'BaseMesh', 'make a new one with new BaseMesh(mesh)'],
  [Evaluator, 'Evaluator', 'build a new one with baseMesh.evaluator(options) (an evaluator outlives its BaseMesh, not its own free())'],
];

const GUARDED = Symbol.for('subsurf.freedGuard');

for (const [type, name, remedy] of REMEDIES) {
  const proto = type.prototype;
  if (proto[GUARDED]) continue;
  Object.defineProperty(proto, GUARDED, { value: true });
  for (const key of Object.getOwnPropertyNames(proto)) {
    // The constructor and the glue's own helpers (__wrap, __destroy_into_raw) are not the
    // user's calls.
    if (key === 'constructor' || key.startsWith('__')) continue;
    const member = Object.getOwnPropertyDescriptor(proto, key);
    if (key === 'free') {
      // A second free() does nothing, as three.js's dispose().
      const free = member.value;
      member.value = function () {
        if (this.__wbg_ptr !== 0) free.call(this);
      };
      Object.defineProperty(proto, key, member);
      continue;
    }
    const check = (self) => {
      if (self != null && self.__wbg_ptr === 0) {
        throw new Error(`subsurf: ${name}.${key} called after free(); ${remedy}`);
      }
    };
    if (typeof member.value === 'function') {
      const method = member.value;
      member.value = function (...args) {
        check(this);
        return method.apply(this, args);
      };
    }
    if (member.get) {
      const get = member.get;
      member.get = function () {
        check(this);
        return get.call(this);
      };
    }
    if (member.set) {
      const set = member.set;
      member.set = function (value) {
        check(this);
        set.call(this, value);
      };
    }
    Object.defineProperty(proto, key, member);
  }
  // The glue set this to the unwrapped free().
  if (Symbol.dispose && proto[Symbol.dispose]) proto[Symbol.dispose] = proto.free;
}
