#!/usr/bin/python3
"""BAR-WAVE-2D with the peer code PySPH (ElasticSolidsScheme), for bench-peers.

The common benchmark is specified in docs/theory.md §8.11: a plane
P-wave in a linear elastic bar, 0 <= x <= L = 1 m, height H = 0.25 m, plane
strain, E = 150 MPa, nu = 0.25, rho = 2000 kg/m^3 (K = 100 MPa, G = 60 MPa,
constrained modulus K + 4G/3 = 180 MPa, c_p = 300 m/s).  The left face is a
piston moving at V0 = 0.3 m/s from t = 0, the right face is free, and the top
and bottom symmetry planes are replaced by periodicity in y (equivalent for
this plane wave).  Units are SI throughout (m, s, kg, Pa); stresses are total
stresses, tension positive: sigma = -p I + s.

Usage (run with the Debian PySPH, /usr/bin/python3)::

    bench/peers/pysph_bar_wave_2d.py --size {t,s,m,l,xl} --out DIR
        [--steps N | --end-transits X] [--openmp]

--steps N          timing mode: set up and compile (not timed), then time
                   exactly N steps (probes on); writes DIR/pysph-SIZE-tT.json,
                   T = OMP_NUM_THREADS with --openmp (else the core count),
                   1 without.
--end-transits X   accuracy mode: run to t = X L / c_p; writes
                   DIR/pysph-SIZE-probes.csv (one row per step, t = 0
                   included) and the same JSON as timing mode.
--openmp           let PySPH compile its loops with OpenMP.

PySPH writes its log and info file into DIR/pysph-SIZE-output (field output
is disabled) and its compiled extension into ~/.pysph/source; nothing is
written to the source tree.

Construction
------------
* Bar ("bar", the elastic solid): the lattice of the rktsph case files
  cases/bar-wave-2d-SIZE/case.yaml, spacing dx, columns x0 = i dx,
  i = 1..nx (nx = L/dx; the rktsph column x = 0 is the piston, below), rows
  y0 = (j + 1/2) dx, j = 0..ny-1 (ny = H/dx), periodic in y with period H by
  PySPH's DomainManager(periodic_in_y=True).  Particle mass rho dx^2.
* Piston ("piston"): three columns of particles at x0 = 0, -dx, -2dx (a slab
  3 dx thick, more than the kernel support 2.6 dx of the first bar column),
  same rows and mass, velocity (V0, 0) from t = 0. The piston is a second
  *elastic* solid of the scheme whose motion is imposed: PistonStep below is
  PySPH's SolidMechStep with the velocity held fixed, so x = x0 + V0 t exactly
  at every stage while its density and deviatoric stress evolve by the
  scheme's own rates (the equivalent of the rktsph column x = 0, a node with
  imposed velocity). The piston's velocity gradient, and so its stress, come
  from its bar neighbours: its front column carries the bar's compression
  (-195 kPa against -184 kPa in the first bar column at size T, t = 3 ms), so
  the face transmits the full traction. The other construction, the piston as
  the scheme's ``solids`` (zero p and s, rho = rho0, as the wall of PySPH's
  oscillating_plate.py; moved by TwoStageRigidBodyStep), was tried and
  rejected: zero-stress neighbours transmit too little traction, the bar
  creeps into the piston and at size T the plateau is v_x = 0.273 m/s,
  sigma_xx = -163.6 kPa (-9.1 %), tension -28 %.
* Periodic ghosts: ElasticSolidsScheme puts the EOS, velocity gradient and
  artificial stress in a group that runs on real particles only, so the
  periodic ghosts (copied at each domain update) carry p, grad v and R one
  stage old into the momentum and continuity sums; near y = 0 and y = H
  this made |v_y| up to 1.2e-2 V0 at the piston start.  That group is run
  on the ghosts as well (Group.real = False, as PySPH's WCSPHScheme does for
  its EOS group; the ghost layers are 2 supports deep, PySPH's default), and
  the plane wave then keeps |v_y| at round-off.
* Scheme: ElasticSolidsScheme (Gray, Monaghan & Swift 2001) with PySPH's
  defaults: artificial viscosity alpha = beta = 1 (eta = 0.1 h), artificial
  stress eps = 0.3 with n = 4 and W(dx) as reference (wdeltap, as in
  oscillating_plate.py), XSPH eps = 0.5, EPEC predictor-corrector
  integrator, cubic spline kernel with h = 1.3 dx (support 2.6 dx),
  fixed time step dt = 0.3 dx / c_p.  Linked-list NNPS (PySPH default).
  The defaults are stable here.  The artificial stress acts in tension
  only: the tension plateau at size T is +193 kPa instead of +180 kPa
  (+0.3 % with artificial_stress_eps = 0); compression is unaffected.
* Elastic constants: the scheme takes E and nu and uses
  c0^2 = E / (3 (1 - 2 nu) rho0) = K / rho0 in the isothermal EOS
  p = c0^2 (rho - rho0) (with the continuity equation, dp = -K tr(D) dt) and
  G = E / (2 (1 + nu)) in the Jaumann deviatoric rate
  ds/dt = 2G (D - tr(D)/3 I) + rotation terms.  In 2D, VelocityGradient2D
  leaves v22 = 0, so tr(D) = D00 + D11 (plane strain, the 1/3 trace factor
  is the 3D one and is right).  In uniaxial strain (D00 only) this gives
  d sigma_xx = (K + 4G/3) D00 dt = 180 MPa D00 dt and
  d sigma_yy = (K - 2G/3) D00 dt = 60 MPa D00 dt, i.e. c_p = 300 m/s and
  sigma_yy / sigma_xx = nu / (1 - nu) = 1/3, as the benchmark requires.
  (The artificial viscosity uses the bulk speed c0 = 223.6 m/s, PySPH's
  choice.)

Probes (Lagrangian, by initial position, index arrays precomputed): mid =
the bar particles with |x0 - L/2| < dx (strict, i.e. the one column at
x0 = L/2), end = the last column x0 = L, all = every bar particle.  The
pressure used in sigma is the scheme's EOS applied to the current density
(PySPH's p array holds the value of the last mid-step evaluation).
"""

import argparse
import json
import math
import os
import resource
import sys
import time

import numpy as np

try:
    from pysph.sph.integrator_step import IntegratorStep
except ImportError as error:
    sys.exit('pysph_bar_wave_2d: error: cannot import PySPH (%s); run it '
             'with /usr/bin/python3 and the Debian python3-pysph' % error)

# Benchmark constants (SI).
LENGTH = 1.0
HEIGHT = 0.25
YOUNG = 1.5e8
POISSON = 0.25
DENSITY = 2000.0
V0 = 0.3
H_OVER_DX = 1.3
COURANT = 0.3
PISTON_LAYERS = 3
BULK = YOUNG / (3.0 * (1.0 - 2.0 * POISSON))
SHEAR = YOUNG / (2.0 * (1.0 + POISSON))
C_P = math.sqrt((BULK + 4.0 * SHEAR / 3.0) / DENSITY)
SPACINGS = {'t': 0.01, 's': 0.005, 'm': 0.0025, 'l': 0.00125, 'xl': 0.0005}
CSV_HEADER = ('time,mid.velocity_x,mid.stress_xx,mid.stress_yy,'
              'end.velocity_x,all.velocity_y')


class PistonStep(IntegratorStep):
    """PySPH's SolidMechStep with the velocity held at its value.

    The piston is an elastic body whose motion is imposed: positions advance
    with the (constant) velocity u, density and deviatoric stress are
    integrated from the scheme's rates exactly as SolidMechStep does, and
    the computed accelerations au, av are ignored.
    """

    def initialize(self, d_idx, d_x0, d_y0, d_x, d_y, d_rho0, d_rho,
                   d_s00, d_s01, d_s02, d_s11, d_s12, d_s22,
                   d_s000, d_s010, d_s020, d_s110, d_s120, d_s220):
        d_x0[d_idx] = d_x[d_idx]
        d_y0[d_idx] = d_y[d_idx]
        d_rho0[d_idx] = d_rho[d_idx]
        d_s000[d_idx] = d_s00[d_idx]
        d_s010[d_idx] = d_s01[d_idx]
        d_s020[d_idx] = d_s02[d_idx]
        d_s110[d_idx] = d_s11[d_idx]
        d_s120[d_idx] = d_s12[d_idx]
        d_s220[d_idx] = d_s22[d_idx]

    def stage1(self, d_idx, d_x0, d_y0, d_x, d_y, d_u, d_v, d_rho0,
               d_rho, d_arho, d_s00, d_s01, d_s02, d_s11, d_s12, d_s22,
               d_s000, d_s010, d_s020, d_s110, d_s120, d_s220, d_as00,
               d_as01, d_as02, d_as11, d_as12, d_as22, dt):
        dtb2 = 0.5 * dt
        d_x[d_idx] = d_x0[d_idx] + dtb2 * d_u[d_idx]
        d_y[d_idx] = d_y0[d_idx] + dtb2 * d_v[d_idx]
        d_rho[d_idx] = d_rho0[d_idx] + dtb2 * d_arho[d_idx]
        d_s00[d_idx] = d_s000[d_idx] + dtb2 * d_as00[d_idx]
        d_s01[d_idx] = d_s010[d_idx] + dtb2 * d_as01[d_idx]
        d_s02[d_idx] = d_s020[d_idx] + dtb2 * d_as02[d_idx]
        d_s11[d_idx] = d_s110[d_idx] + dtb2 * d_as11[d_idx]
        d_s12[d_idx] = d_s120[d_idx] + dtb2 * d_as12[d_idx]
        d_s22[d_idx] = d_s220[d_idx] + dtb2 * d_as22[d_idx]

    def stage2(self, d_idx, d_x0, d_y0, d_x, d_y, d_u, d_v, d_rho0,
               d_rho, d_arho, d_s00, d_s01, d_s02, d_s11, d_s12, d_s22,
               d_s000, d_s010, d_s020, d_s110, d_s120, d_s220, d_as00,
               d_as01, d_as02, d_as11, d_as12, d_as22, dt):
        d_x[d_idx] = d_x0[d_idx] + dt * d_u[d_idx]
        d_y[d_idx] = d_y0[d_idx] + dt * d_v[d_idx]
        d_rho[d_idx] = d_rho0[d_idx] + dt * d_arho[d_idx]
        d_s00[d_idx] = d_s000[d_idx] + dt * d_as00[d_idx]
        d_s01[d_idx] = d_s010[d_idx] + dt * d_as01[d_idx]
        d_s02[d_idx] = d_s020[d_idx] + dt * d_as02[d_idx]
        d_s11[d_idx] = d_s110[d_idx] + dt * d_as11[d_idx]
        d_s12[d_idx] = d_s120[d_idx] + dt * d_as12[d_idx]
        d_s22[d_idx] = d_s220[d_idx] + dt * d_as22[d_idx]


def fail(message):
    """Print an error message to stderr and exit with status 1."""
    sys.stderr.write('pysph_bar_wave_2d: error: %s\n' % message)
    sys.exit(1)


def parse_arguments():
    parser = argparse.ArgumentParser(
        description='BAR-WAVE-2D with PySPH (ElasticSolidsScheme).')
    parser.add_argument('--size', required=True, choices=sorted(SPACINGS))
    parser.add_argument('--out', required=True, help='output directory')
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument('--steps', type=int,
                      help='timing mode: number of steps to time')
    mode.add_argument('--end-transits', type=float,
                      help='accuracy mode: end time in units of L / c_p')
    parser.add_argument('--openmp', action='store_true',
                        help='compile and run with OpenMP')
    args = parser.parse_args()
    if args.steps is not None and args.steps < 1:
        parser.error('--steps must be at least 1')
    if args.end_transits is not None and not args.end_transits > 0.0:
        parser.error('--end-transits must be positive')
    return args


def main():
    args = parse_arguments()
    try:
        run(args)
    except Exception as error:  # PySPH setup, compilation or run failure
        fail('%s: %s' % (type(error).__name__, error))


def run(args):
    wall_start = time.perf_counter()

    # The rest of PySPH is imported here, after the argument checks.
    import pysph
    from compyle.config import get_config
    from pysph.base.kernels import CubicSpline
    from pysph.base.nnps import DomainManager
    from pysph.solver.application import Application
    from pysph.sph.solid_mech.basic import (
        ElasticSolidsScheme, get_particle_array_elastic_dynamics)

    dx = SPACINGS[args.size]
    nx = int(round(LENGTH / dx))
    ny = int(round(HEIGHT / dx))
    dt = COURANT * dx / C_P
    if args.steps is not None:
        nsteps = args.steps
    else:
        # Steps to reach X L / c_p (the bench table's counts, e.g. 417 and
        # 1000 at T); the last step ends at or just after the end time.
        nsteps = int(math.ceil(args.end_transits * LENGTH / C_P / dt - 1e-6))
    if args.openmp:
        threads = int(os.environ.get('OMP_NUM_THREADS', os.cpu_count()))
    else:
        threads = 1

    out_dir = os.path.abspath(args.out)
    os.makedirs(out_dir, exist_ok=True)
    tag = 'pysph-%s' % args.size
    pysph_dir = os.path.join(out_dir, tag + '-output')

    class BarWave2D(Application):
        """The benchmark as a PySPH application (see the module docstring)."""

        def initialize(self):
            self.dx = dx
            self.h = H_OVER_DX * dx
            self.probe_rows = []
            self.t_start = None

        def create_domain(self):
            return DomainManager(ymin=0.0, ymax=HEIGHT, periodic_in_y=True)

        def create_particles(self):
            m = DENSITY * dx * dx
            kernel = CubicSpline(dim=2)
            wdeltap = kernel.kernel(rij=dx, h=self.h)
            consts = dict(E=YOUNG, nu=POISSON, rho_ref=DENSITY)
            ii, jj = np.meshgrid(np.arange(1, nx + 1), np.arange(ny),
                                 indexing='ij')
            xb = (ii * dx).ravel()
            yb = ((jj + 0.5) * dx).ravel()
            bar = get_particle_array_elastic_dynamics(
                x=xb, y=yb, m=m, h=self.h, rho=DENSITY, name='bar',
                constants=dict(consts, wdeltap=wdeltap, n=4))
            bar.add_property('index0', data=np.arange(xb.size, dtype=float))
            ip, jp = np.meshgrid(-np.arange(PISTON_LAYERS), np.arange(ny),
                                 indexing='ij')
            xp = (ip * dx).ravel()
            piston = get_particle_array_elastic_dynamics(
                x=xp, y=((jp + 0.5) * dx).ravel(), m=m, h=self.h,
                rho=DENSITY, u=np.full(xp.size, V0), name='piston',
                constants=dict(consts, wdeltap=wdeltap, n=4))

            # Probe index arrays, by initial position (and column index).
            self.nodes = xb.size
            self.piston_particles = xp.size
            self.mid = np.flatnonzero(
                np.abs(xb - 0.5 * LENGTH) < (1.0 - 1e-9) * dx)
            self.end = np.flatnonzero(ii.ravel() == nx)
            self.c0sq = bar.c0_ref[0] ** 2
            return [bar, piston]

        def create_scheme(self):
            scheme = ElasticSolidsScheme(elastic_solids=['bar', 'piston'],
                                         solids=[], dim=2)
            scheme.configure_solver(
                kernel=CubicSpline(dim=2), dt=dt, tf=nsteps * dt,
                extra_steppers={'piston': PistonStep()})
            return scheme

        def create_equations(self):
            equations = self.scheme.get_equations()
            # Evaluate the first group (EOS, velocity gradient, artificial
            # stress) on the periodic ghosts too, as WCSPHScheme does for
            # its EOS group, so that the second group reads current p, r.
            equations[0].real = False
            return equations

        def probe(self, t):
            bar = self.particles[0]
            mid, n = self.mid, self.nodes
            p_mid = self.c0sq * (bar.rho[mid] - DENSITY)
            self.probe_rows.append((
                t,
                bar.u[mid].mean(),
                (bar.s00[mid] - p_mid).mean(),
                (bar.s11[mid] - p_mid).mean(),
                bar.u[self.end].mean(),
                np.abs(bar.v[:n]).max()))

        def pre_step(self, solver):
            if self.t_start is None:
                self.t_start = time.perf_counter()

        def post_step(self, solver):
            # Called before the solver advances t: the step ends at t + dt.
            self.probe(solver.t + solver.dt)

    app = BarWave2D(fname=tag, output_dir=pysph_dir)
    pysph_args = ['-d', pysph_dir, '--disable-output', '-q',
                  '--timestep', repr(dt), '--tf', repr(nsteps * dt),
                  '--max-steps', str(nsteps)]
    if args.openmp:
        # compyle's parser option, which sets its config.use_openmp.
        pysph_args.append('--openmp')
    app.setup(pysph_args)
    if get_config().use_openmp != args.openmp:
        fail('PySPH did not take the OpenMP setting')
    solver = app.solver
    bar = app.particles[0]
    if bar.num_real_particles != app.nodes:
        fail('bar has %d real particles, expected %d'
             % (bar.num_real_particles, app.nodes))
    if app.mid.size != ny or app.end.size != ny:
        fail('probe groups have %d (mid) and %d (end) particles, expected %d'
             % (app.mid.size, app.end.size, ny))
    app.probe(0.0)

    # The initial acceleration evaluation inside solve() comes before the
    # first pre_step call, so it counts as setup; only the steps are timed.
    solver.solve(show_progress=False)
    t_end = time.perf_counter()
    if app.t_start is None:
        fail('the solver took no step')
    seconds = t_end - app.t_start
    setup_seconds = app.t_start - wall_start

    # Checks: step count, particle order, finite final state.
    if solver.count != nsteps or len(app.probe_rows) != nsteps + 1:
        fail('took %d steps, expected %d' % (solver.count, nsteps))
    if not np.array_equal(bar.index0, np.arange(app.nodes)):
        fail('PySPH reordered the bar particles; probes are invalid')
    for name in ('x', 'y', 'u', 'v', 'rho', 's00', 's01', 's11', 's22'):
        if not np.all(np.isfinite(getattr(bar, name))):
            fail('non-finite %s in the final state (unstable run)' % name)
    rows = np.array(app.probe_rows)
    if not np.all(np.isfinite(rows)):
        fail('non-finite probe values')

    seconds_per_step = seconds / nsteps
    result = {
        'code': 'pysph',
        'version': pysph.__version__,
        'size': args.size,
        'nodes': int(app.nodes),
        'piston_particles': int(app.piston_particles),
        'threads': threads,
        'steps': int(nsteps),
        'seconds_per_step': seconds_per_step,
        'particle_steps_per_second': app.nodes / seconds_per_step,
        'setup_seconds': setup_seconds,
        'h_over_dx': H_OVER_DX,
        'dt': dt,
        'peak_rss_mb': resource.getrusage(
            resource.RUSAGE_SELF).ru_maxrss / 1024.0,
    }
    json_path = os.path.join(out_dir, '%s-t%d.json' % (tag, threads))
    with open(json_path, 'w') as stream:
        json.dump(result, stream, indent=2)
        stream.write('\n')
    written = [json_path]
    if args.end_transits is not None:
        csv_path = os.path.join(out_dir, tag + '-probes.csv')
        np.savetxt(csv_path, rows, delimiter=',', fmt='%.10e',
                   header=CSV_HEADER, comments='')
        written.append(csv_path)

    print('pysph %s: %d nodes, %d steps of %.4g s, %d thread(s): '
          '%.4g s/step, %.4g particle-steps/s, setup %.1f s -> %s'
          % (args.size, app.nodes, nsteps, dt, threads, seconds_per_step,
             app.nodes / seconds_per_step, setup_seconds,
             ', '.join(written)))


if __name__ == '__main__':
    main()
