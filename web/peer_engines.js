// The engines people run in browsers, beside boxsim's techniques on the page: Jolt Physics
// (npm jolt-physics, Jolt compiled to WebAssembly) and Rapier (npm @dimforge/rapier3d-compat).
// Each builds the scene boxsim builds: the same boxes (half extents, poses, velocities, masses;
// the ground and the waiting shots fixed), the same gravity, restitution, friction μ and
// Δt = 1/60 s, from the boxsim Demo of that scene (Demo.sceneBodies, demo.hpp), which is not
// stepped but measures: penetration() is boxsim's separating-axis test at the engine's poses
// (Demo.penetrationAt), the yardstick of every engine (as bench/peers measures Bullet and ODE).
// Otherwise each is configured as its own documentation advises, at its defaults:
//
// - Jolt: one JoltInterface of the single-threaded WebAssembly build, two object layers
//   (fixed, moving) each with its broad-phase layer, as its hello-world example; BoxShape with
//   its default convex radius (0.05 m); the mass given with the inertia computed from the shape
//   (EOverrideMassProperties_CalculateInertia); OptimizeBroadPhase() once the scene is added, as
//   its docs ask after adding many bodies; Step(Δt, 1); sleeping on (its default). It combines
//   two bodies' friction by the geometric mean and restitution by the maximum, so equal values
//   combine to themselves.
// - Rapier: World with its default integration parameters (4 solver iterations), timestep Δt;
//   a cuboid collider per body with its mass given (setMass: inertia from the shape); sleeping
//   on (its default). Friction and restitution combine by the average.
//
// A run answers what the worker asks of boxsim's Demo: step(), time(), poses() (7 a body: x, y,
// z, then the quaternion's x, y, z, w), flags(), halfExtents(), largestDisplacement(),
// shotsLeft(), shoot(from, direction), penetration(), delete(). A shot enters at the next step,
// from its point at the speed of boxsim's shots (Module.shotSpeed), as boxsim launches it.

const DT = 1 / 60;  // s
const FLAG_IMMOVABLE = 1, FLAG_ASLEEP = 2;  // demo.hpp, BodyFlag
const PER_BODY = 17;  // numbers a body of Demo.sceneBodies

// The engines' modules, loaded once and only when asked for (each is a few megabytes).
let jolt = null, rapier = null;
async function loadJolt() {
  if (!jolt) jolt = (await import('./jolt-physics.wasm-compat.js')).default();
  return jolt;
}
async function loadRapier() {
  if (!rapier) {
    rapier = import('./rapier.mjs').then(async ({ default: RAPIER }) => {
      await RAPIER.init();
      return RAPIER;
    });
  }
  return rapier;
}

// What both engines share: the scene read from boxsim's Demo, the poses kept in Demo's layout,
// the shots, the displacement and the measure.
class PeerRun {
  constructor(Module, probe) {
    this.probe = probe;
    this.bodies = probe.sceneBodies();
    this.count = this.bodies.length / PER_BODY;
    this.firstShot = this.count - Module.shotCount;
    this.shotSpeed = Module.shotSpeed;
    this.fired = 0;
    this.steps = 0;
    this.waiting = [];  // shots fired since the last step: { index, from, velocity }
    this.posesOut = new Float64Array(7 * this.count);
    this.asleep = new Uint8Array(this.count);
    this.moving = new Uint8Array(this.count);  // a body the engine moves
    this.start = [];
    for (let i = 0; i < this.count; ++i) {
      const b = this.body(i);
      this.posesOut.set([...b.x, ...b.q], 7 * i);
      this.moving[i] = b.mass > 0 ? 1 : 0;
      this.start.push(b.x);
    }
  }
  // Body i of the scene: half extents, position, quaternion (x, y, z, w), velocity, angular
  // velocity, mass (0: fixed).
  body(i) {
    const s = this.bodies.subarray(PER_BODY * i, PER_BODY * (i + 1));
    return { half: [...s.subarray(0, 3)], x: [...s.subarray(3, 6)], q: [...s.subarray(6, 10)],
             v: [...s.subarray(10, 13)], omega: [...s.subarray(13, 16)], mass: s[16] };
  }
  time() { return this.steps * DT; }
  poses() { return this.posesOut; }
  flags() {
    const f = new Uint8Array(this.count);
    for (let i = 0; i < this.count; ++i)
      f[i] = (this.moving[i] ? 0 : FLAG_IMMOVABLE) | (this.asleep[i] ? FLAG_ASLEEP : 0);
    return f;
  }
  halfExtents() {
    const out = [];
    for (let i = 0; i < this.count; ++i) out.push(...this.body(i).half);
    return out;
  }
  largestDisplacement() {
    let largest = 0;
    for (let i = 0; i < this.firstShot; ++i) {
      if (!this.moving[i]) continue;
      const p = this.posesOut, s = this.start[i];
      largest = Math.max(largest, Math.hypot(p[7 * i] - s[0], p[7 * i + 1] - s[1], p[7 * i + 2] - s[2]));
    }
    return largest;
  }
  shotsLeft() { return this.count - this.firstShot - this.fired; }
  shoot(fx, fy, fz, dx, dy, dz) {
    const length = Math.hypot(dx, dy, dz);
    if (this.shotsLeft() === 0 || !(length > 0)) return false;
    const index = this.firstShot + this.fired++;
    const k = this.shotSpeed / length;
    this.waiting.push({ index, from: [fx, fy, fz], velocity: [k * dx, k * dy, k * dz] });
    this.posesOut.set([fx, fy, fz, 0, 0, 0, 1], 7 * index);
    this.start[index] = [fx, fy, fz];
    return true;
  }
  step() {
    for (const shot of this.waiting) {
      this.launch(shot);
      this.moving[shot.index] = 1;
    }
    this.waiting = [];
    this.advance();
    ++this.steps;
    this.readBack();
    return 0;
  }
  penetration() { return this.probe.penetrationAt(this.posesOut); }
  delete() {
    this.destroy();
    this.probe.delete();
  }
}

/// Jolt Physics (the single-threaded WebAssembly build of npm jolt-physics).
class JoltRun extends PeerRun {
  constructor(Jolt, Module, probe, friction) {
    super(Module, probe);
    this.Jolt = Jolt;
    const FIXED = 0, MOVING = 1;
    this.layers = { FIXED, MOVING };
    const settings = new Jolt.JoltSettings();
    settings.mMaxBodies = Math.max(settings.mMaxBodies, this.count);
    const pairs = new Jolt.ObjectLayerPairFilterTable(2);
    pairs.EnableCollision(FIXED, MOVING);
    pairs.EnableCollision(MOVING, MOVING);
    const bpFixed = new Jolt.BroadPhaseLayer(0), bpMoving = new Jolt.BroadPhaseLayer(1);
    const bp = new Jolt.BroadPhaseLayerInterfaceTable(2, 2);
    bp.MapObjectToBroadPhaseLayer(FIXED, bpFixed);
    bp.MapObjectToBroadPhaseLayer(MOVING, bpMoving);
    settings.mObjectLayerPairFilter = pairs;
    settings.mBroadPhaseLayerInterface = bp;
    settings.mObjectVsBroadPhaseLayerFilter = new Jolt.ObjectVsBroadPhaseLayerFilterTable(bp, 2, pairs, 2);
    this.jolt = new Jolt.JoltInterface(settings);
    Jolt.destroy(settings);
    this.system = this.jolt.GetPhysicsSystem();
    this.bodyInterface = this.system.GetBodyInterface();
    const gravity = new Jolt.Vec3(0, -probe.gravity(), 0);
    this.system.SetGravity(gravity);
    Jolt.destroy(gravity);
    this.restitution = probe.restitution();
    this.friction = friction;
    this.ids = [];
    this.handles = [];
    for (let i = 0; i < this.count; ++i) this.add(i, this.moving[i] === 1, null);
    this.system.OptimizeBroadPhase();
  }
  // Adds body i, moving or fixed; a shot (launch) replaces its fixed waiting body.
  add(i, moving, launch) {
    const Jolt = this.Jolt, b = this.body(i);
    const half = new Jolt.Vec3(...b.half);
    const shape = new Jolt.BoxShape(half);
    const x = launch ? launch.from : b.x, q = launch ? [0, 0, 0, 1] : b.q;
    const position = new Jolt.RVec3(...x), rotation = new Jolt.Quat(...q);
    const settings = new Jolt.BodyCreationSettings(
      shape, position, rotation, moving ? Jolt.EMotionType_Dynamic : Jolt.EMotionType_Static,
      moving ? this.layers.MOVING : this.layers.FIXED);
    settings.mRestitution = this.restitution;
    settings.mFriction = this.friction;
    if (moving) {
      settings.mOverrideMassProperties = Jolt.EOverrideMassProperties_CalculateInertia;
      settings.mMassPropertiesOverride.mMass = launch ? 1.0 : b.mass;
      const v = new Jolt.Vec3(...(launch ? launch.velocity : b.v));
      const w = new Jolt.Vec3(...(launch ? [0, 0, 0] : b.omega));
      settings.mLinearVelocity = v;
      settings.mAngularVelocity = w;
      Jolt.destroy(v);
      Jolt.destroy(w);
    }
    const body = this.bodyInterface.CreateBody(settings);
    this.bodyInterface.AddBody(body.GetID(), moving ? Jolt.EActivation_Activate : Jolt.EActivation_DontActivate);
    this.ids[i] = body.GetID();
    this.handles[i] = body;
    for (const o of [half, position, rotation, settings]) Jolt.destroy(o);
  }
  launch(shot) {
    this.bodyInterface.RemoveBody(this.ids[shot.index]);
    this.bodyInterface.DestroyBody(this.ids[shot.index]);
    this.add(shot.index, true, shot);
  }
  advance() { this.jolt.Step(DT, 1); }
  readBack() {
    for (let i = 0; i < this.count; ++i) {
      if (!this.moving[i]) continue;
      const body = this.handles[i], p = body.GetPosition(), q = body.GetRotation(), o = 7 * i;
      this.posesOut[o] = p.GetX(); this.posesOut[o + 1] = p.GetY(); this.posesOut[o + 2] = p.GetZ();
      this.posesOut[o + 3] = q.GetX(); this.posesOut[o + 4] = q.GetY();
      this.posesOut[o + 5] = q.GetZ(); this.posesOut[o + 6] = q.GetW();
      this.asleep[i] = body.IsActive() ? 0 : 1;
    }
  }
  destroy() {
    for (let i = 0; i < this.count; ++i) {
      this.bodyInterface.RemoveBody(this.ids[i]);
      this.bodyInterface.DestroyBody(this.ids[i]);
    }
    this.Jolt.destroy(this.jolt);
  }
}

/// Rapier (npm @dimforge/rapier3d-compat).
class RapierRun extends PeerRun {
  constructor(RAPIER, Module, probe, friction) {
    super(Module, probe);
    this.RAPIER = RAPIER;
    this.world = new RAPIER.World({ x: 0, y: -probe.gravity(), z: 0 });
    this.world.timestep = DT;
    this.restitution = probe.restitution();
    this.friction = friction;
    this.handles = [];
    for (let i = 0; i < this.count; ++i) this.add(i, this.moving[i] === 1, null);
  }
  add(i, moving, launch) {
    const RAPIER = this.RAPIER, b = this.body(i);
    const x = launch ? launch.from : b.x, q = launch ? [0, 0, 0, 1] : b.q;
    const v = launch ? launch.velocity : b.v, w = launch ? [0, 0, 0] : b.omega;
    const desc = (moving ? RAPIER.RigidBodyDesc.dynamic() : RAPIER.RigidBodyDesc.fixed())
      .setTranslation(...x).setRotation({ x: q[0], y: q[1], z: q[2], w: q[3] });
    if (moving) desc.setLinvel(...v).setAngvel({ x: w[0], y: w[1], z: w[2] });
    const body = this.world.createRigidBody(desc);
    const collider = RAPIER.ColliderDesc.cuboid(...b.half)
      .setRestitution(this.restitution).setFriction(this.friction);
    if (moving) collider.setMass(launch ? 1.0 : b.mass);
    this.world.createCollider(collider, body);
    this.handles[i] = body;
  }
  launch(shot) {
    this.world.removeRigidBody(this.handles[shot.index]);
    this.add(shot.index, true, shot);
  }
  advance() { this.world.step(); }
  readBack() {
    for (let i = 0; i < this.count; ++i) {
      if (!this.moving[i]) continue;
      const body = this.handles[i], p = body.translation(), q = body.rotation(), o = 7 * i;
      this.posesOut[o] = p.x; this.posesOut[o + 1] = p.y; this.posesOut[o + 2] = p.z;
      this.posesOut[o + 3] = q.x; this.posesOut[o + 4] = q.y; this.posesOut[o + 5] = q.z;
      this.posesOut[o + 6] = q.w;
      this.asleep[i] = body.isSleeping() ? 1 : 0;
    }
  }
  destroy() { this.world.free(); }
}

/// The engines of the page besides boxsim's techniques, by the name of the technique selector.
export const PEER_ENGINES = ['jolt', 'rapier'];

/// A run of `scene` under engine `name` ('jolt' or 'rapier') with friction μ, built from a
/// boxsim Demo of the same scene; the Demo is the run's own (deleted with it).
export async function makePeerRun(name, Module, scene, friction) {
  if (!PEER_ENGINES.includes(name))
    throw new Error(`unknown engine '${name}'; the page has ${PEER_ENGINES.join(', ')}`);
  const engine = name === 'jolt' ? await loadJolt() : await loadRapier();
  const probe = new Module.Demo(scene, 'damped', true, true, 'none', friction);
  try {
    return name === 'jolt' ? new JoltRun(engine, Module, probe, friction)
                           : new RapierRun(engine, Module, probe, friction);
  } catch (error) {
    probe.delete();
    throw error;
  }
}
