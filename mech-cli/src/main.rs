//! `mech`: planar mechanisms from a terminal (`docs/cli.md`). Each subcommand reads a
//! mechanism file (`*.mech`: the text between the braces of `mechanism! { ... }`), or
//! standard input with `-`.

use clap::{Parser, Subcommand};
use mech_cli::columns::Level;
use mech_cli::loads::LoadSet;
use mech_cli::output::Format;
use mech_cli::{
    balance, cam, check, draw, engine, flywheel, import, limits, optimize, quantity, regime,
    report, serve, shaking, simulate, size, solve, source, spatial, strength, synth, synth_exact,
    Failure,
};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Dynamics of planar machines: check, solve, sweep, size a flywheel, simulate, draw.
///
/// Numbers are SI, or carry one unit word glued or spaced: `--at 30deg`, `--at "30 deg"`,
/// `--speed 3000rpm`, `--load gas=-1.5kN,0`. Output data (SI units, named in the table
/// header) go to standard output, messages and progress to standard error.
#[derive(Parser, Debug)]
#[command(name = "mech", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The options of a configuration: inputs, rates, loads, output.
#[derive(clap::Args, Debug)]
struct State {
    /// Input speeds q̇, one per input (rad/s or m/s; `rpm` allowed); default 0.
    #[arg(long = "speed", value_delimiter = ',', allow_hyphen_values = true)]
    speed: Vec<String>,
    /// Input accelerations q̈, one per input (rad/s² or m/s²); default 0.
    #[arg(long = "accel", value_delimiter = ',', allow_hyphen_values = true)]
    accel: Vec<String>,
    /// A load: NAME=VALUE (`gas=-1500,0` N, `shaft=-4` N·m) or NAME=@table.csv (columns q
    /// or q_deg, then the value(s); linear, repeating with the table's span). Repeatable.
    #[arg(long = "load", allow_hyphen_values = true)]
    load: Vec<String>,
    /// What to compute: positions, kinematics, or forces (reactions, motor actions by
    /// d'Alembert and by virtual power, I*, M*).
    #[arg(long, value_enum, default_value_t = Level::Forces)]
    level: Level,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    format: Format,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the macro's checks; print the structure (Grübler, Assur groups; Kutzbach's count
    /// and the idle links for a spatial mechanism) or the errors as FILE:LINE:COLUMN with
    /// an excerpt. Exit status 1 for a bad mechanism.
    Check {
        /// The mechanism file (`-` = standard input).
        file: PathBuf,
    },
    /// One configuration: every point and link, every reaction, the motor actions by
    /// both routes, I* and M*. A spatial mechanism (`space` first) takes loads as
    /// NAME=x,y,z.
    Solve {
        /// The mechanism file (`-` = standard input).
        file: PathBuf,
        /// Input values q, one per input (rad or m; `deg`, `mm` allowed).
        #[arg(
            long = "at",
            required = true,
            value_delimiter = ',',
            allow_hyphen_values = true
        )]
        at: Vec<String>,
        #[command(flatten)]
        state: State,
    },
    /// The same over a range of the first input, one row per input, in parallel.
    Sweep {
        /// The mechanism file (`-` = standard input).
        file: PathBuf,
        /// First value of the first input.
        #[arg(long, allow_hyphen_values = true)]
        from: String,
        /// Last value of the first input (included).
        #[arg(long, allow_hyphen_values = true)]
        to: String,
        /// Number of steps (rows = steps + 1), at most 10⁸.
        #[arg(long, allow_hyphen_values = true, value_parser = limits::steps)]
        steps: usize,
        /// The other inputs' values (several DOF), in order after the first.
        #[arg(long = "rest", value_delimiter = ',', allow_hyphen_values = true)]
        rest: Vec<String>,
        #[command(flatten)]
        state: State,
    },
    /// Size a flywheel: the cycle's work, ΔE = S_max − S_min, the inertia by the
    /// approximate formula and by Wittenbauer's exact method, checked by integration.
    Flywheel(flywheel::FlywheelArgs),
    /// The direct problem over time (one input): q(t), q̇(t), q̈(t) under a driver and
    /// loads given as constants or tables against q.
    Simulate(simulate::SimulateArgs),
    /// The periodic steady regime under a motor (one revolute input): the mean speed, the
    /// irregularity ε, the period in time, the motor's duty and the table q, q̇ over one
    /// period, found directly (shooting on ω(q0 + λ) = ω(q0)); with --stop, the coast or
    /// braked stop from it: the time to rest, the angle turned, the table t, q, q̇.
    Regime(regime::RegimeArgs),
    /// The strength of every member over the cycle at a constant input speed: one row per
    /// link (a beam `shape:` with a `material:`) or pin (`pin 12 mm`) with the criterion
    /// that governs (axial, bending, shear, bearing, buckling, fatigue), its stresses, the
    /// smallest factor of safety and the q where it is smallest.
    Strength(strength::StrengthArgs),
    /// Size the dimensions written `free(LO..HI)` so that every member's factor of safety
    /// is at least S, re-running the dynamics with each change until a fixed point; print
    /// the passes (total mass, peak driver torque, flywheel, worst factor) and write the
    /// sized file.
    Size(size::SizeArgs),
    /// Vary named numbers of the file (constants, link masses) within bounds to minimise
    /// an objective of its dynamics (peak or RMS driver torque, flywheel, a peak reaction,
    /// the shaking force, a path) under constraints; print the history, write the file.
    Optimize(optimize::OptimizeArgs),
    /// Draw the linkage at one input as SVG: links, pins, slider guides, ground hatching,
    /// point names; a spatial mechanism in an isometric view.
    Draw(draw::DrawArgs),
    /// The linkage moving over a cycle as an animated SVG that plays in any browser.
    Animate(draw::AnimateArgs),
    /// One self-contained HTML page: the animated linkage, a slider for the input, and
    /// plots over the cycle.
    Report(report::ReportArgs),
    /// A cam's profile over a turn: lift, pitch and contact points (the cam's frame),
    /// pressure angle, radius of curvature; the design figures; the surface as SVG.
    Cam(cam::CamArgs),
    /// A mechanism from pyslvs's PMKS expression (`M[J[R, P[x, y], L[ground, L1]], ...]`)
    /// written as a `.mech` file.
    Import(import::ImportArgs),
    /// The shaking force and moment on the frame over a cycle at a constant speed (no loads,
    /// no gravity): one row per input value, peaks, RMS and the primary and secondary
    /// harmonics on standard error, a polar diagram of the force with --svg.
    Shaking(shaking::ShakingArgs),
    /// Write counterweights that balance the shaking force (a four-bar exactly, a
    /// slider-crank's crank for its rotating masses and a fraction of the reciprocating
    /// ones) into a copy of the file; print the shaking force before and after.
    Balance(balance::BalanceArgs),
    /// The workbench: a page on 127.0.0.1 with the linkage drawn and moving, a slider for
    /// each input, the charts against the input (motor torque, I*, M*, each reaction, the
    /// shaking force), the check's errors with the file's line; it follows FILE as it
    /// changes on disk, and dragging a point writes its coordinates into FILE.
    Serve(serve::ServeArgs),
    /// An engine of several cylinders (in-line, V, boxer) on one crankshaft, written as a
    /// `.mech` file with -o; its primary and secondary shaking forces and couples, exact and
    /// to the textbook's first order, on standard output.
    Engine(engine::EngineArgs),
    /// Dimensional synthesis: a four-bar (O2, O4, A, B, P, input O2) from what it must do,
    /// written as a `.mech` file.
    #[command(subcommand)]
    Synth(Synth),
}

/// The synthesis methods of `mech synth`.
#[derive(Subcommand, Debug)]
enum Synth {
    /// Function generation: the output angle (O4 → B) at given input angles (O2 → A), from
    /// a CSV of `input`, `output` (rad): Freudenstein's equation, three pairs exactly, more
    /// by least squares.
    Function(synth_exact::FunctionArgs),
    /// Motion generation: the coupler through given poses, from a CSV of `x`, `y` (P, m)
    /// and `angle` (A → B, rad): Burmester theory, three to five poses exactly, more by
    /// least squares.
    Motion(synth_exact::MotionArgs),
    /// A four-bar whose coupler point P passes nearest to target points (free or
    /// prescribed timing, closed or open path): differential evolution, then a
    /// Levenberg–Marquardt polish; prints the error E = Σ (distance to the curve)².
    Path(synth::PathArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("{}", f.message);
            ExitCode::from(f.status)
        }
    }
}

/// The rates and the loads of `state` for mechanism `m`.
fn rates(
    m: &mech_core::Mechanism,
    state: &State,
) -> Result<(Vec<f64>, Vec<f64>, LoadSet), Failure> {
    let model = m.model();
    Ok((
        quantity::per_input(&state.speed, model, 1, "--speed", 0.0)?,
        quantity::per_input(&state.accel, model, 2, "--accel", 0.0)?,
        LoadSet::parse(&state.load, model)?,
    ))
}

/// The rates and the loads of `state` for the spatial mechanism `m`.
fn spatial_rates(
    m: &mech_core::spatial::SpatialMechanism,
    state: &State,
) -> Result<(Vec<f64>, Vec<f64>, spatial::SpatialLoadSet), Failure> {
    Ok((
        spatial::per_input(&state.speed, m, 1, "--speed", 0.0)?,
        spatial::per_input(&state.accel, m, 2, "--accel", 0.0)?,
        spatial::loads(&state.load, m)?,
    ))
}

/// `mech sweep` of a spatial mechanism.
fn spatial_sweep(
    m: &mech_core::spatial::SpatialMechanism,
    (from, to, steps): (&str, &str, usize),
    rest: &[String],
    state: &State,
    stdout: impl Write,
) -> Result<(), Failure> {
    if m.dof() == 0 {
        return Err(Failure::usage(format!(
            "`{}` has no input: there is no range to sweep; declare an input (`input: J`)",
            m.model().name
        )));
    }
    let (d, _) = spatial::input_dims(m, 0);
    let (a, b) = (
        quantity::parse(from, d, "--from")?,
        quantity::parse(to, d, "--to")?,
    );
    if !(b - a).is_finite() {
        return Err(Failure::usage(format!(
            "--from {from} --to {to}: the range overflows f64; give a narrower range"
        )));
    }
    let g = m.dof();
    if rest.len() + 1 != g {
        return Err(Failure::usage(format!(
            "--rest: {} value(s) for the {} input(s) after the first",
            rest.len(),
            g - 1
        )));
    }
    let mut q = vec![a];
    for (k, t) in rest.iter().enumerate() {
        q.push(quantity::parse(
            t,
            spatial::input_dims(m, k + 1).0,
            "--rest",
        )?);
    }
    let (qd, qdd, loads) = spatial_rates(m, state)?;
    spatial::sweep(
        m,
        (a, b, steps),
        &q,
        &qd,
        &qdd,
        &loads,
        state.level,
        state.format,
        stdout,
    )
}

fn run(command: Command) -> Result<(), Failure> {
    let mut stdout =
        std::io::BufWriter::with_capacity(1 << 16, limits::Stdout(std::io::stdout().lock()));
    match command {
        Command::Check { file } => {
            let text = match source::load_any(&file)? {
                source::Any::Planar(m) => check::summary(&m),
                source::Any::Spatial(m) => spatial::summary(&m),
            };
            write!(stdout, "{text}")?;
            stdout.flush()?;
            Ok(())
        }
        Command::Solve { file, at, state } => {
            let m = match source::load_any(&file)? {
                source::Any::Planar(m) => m,
                source::Any::Spatial(m) => {
                    let q = spatial::per_input(&at, &m, 0, "--at", 0.0)?;
                    let (qd, qdd, loads) = spatial_rates(&m, &state)?;
                    return spatial::solve(
                        &m,
                        &q,
                        &qd,
                        &qdd,
                        &loads.at(q.first().copied().unwrap_or(0.0)),
                        state.level,
                        state.format,
                        stdout,
                    );
                }
            };
            let q = quantity::per_input(&at, m.model(), 0, "--at", 0.0)?;
            let (qd, qdd, loads) = rates(&m, &state)?;
            solve::solve(&m, &q, &qd, &qdd, &loads, state.level, state.format, stdout)
        }
        Command::Sweep {
            file,
            from,
            to,
            steps,
            rest,
            state,
        } => {
            let m = match source::load_any(&file)? {
                source::Any::Planar(m) => m,
                source::Any::Spatial(m) => {
                    return spatial_sweep(&m, (&from, &to, steps), &rest, &state, stdout)
                }
            };
            let model = m.model();
            let (d, _) = quantity::input_dims(model, 0);
            let (a, b) = (
                quantity::parse(&from, d, "--from")?,
                quantity::parse(&to, d, "--to")?,
            );
            if !(b - a).is_finite() {
                return Err(Failure::usage(format!(
                    "--from {from} --to {to}: the range overflows f64; give a narrower range"
                )));
            }
            let g = m.dof();
            if rest.len() + 1 != g {
                return Err(Failure::usage(format!(
                    "--rest: {} value(s) for the {} input(s) after the first",
                    rest.len(),
                    g - 1
                )));
            }
            let mut q = vec![a];
            for (k, t) in rest.iter().enumerate() {
                q.push(quantity::parse(
                    t,
                    quantity::input_dims(model, k + 1).0,
                    "--rest",
                )?);
            }
            let (qd, qdd, loads) = rates(&m, &state)?;
            solve::sweep(
                &m,
                (a, b, steps),
                &q,
                &qd,
                &qdd,
                &loads,
                state.level,
                state.format,
                stdout,
            )
        }
        Command::Flywheel(args) => flywheel::run(args, stdout),
        Command::Simulate(args) => simulate::run(args, stdout),
        Command::Regime(args) => regime::run(args, stdout),
        Command::Strength(args) => strength::run(args, stdout),
        Command::Size(args) => size::run(args, stdout),
        Command::Optimize(args) => optimize::run(args, stdout),
        Command::Draw(args) => draw::draw(args),
        Command::Animate(args) => draw::animate(args),
        Command::Report(args) => report::run(args),
        Command::Import(args) => import::run(args, stdout),
        Command::Cam(args) => cam::run(args, stdout),
        Command::Shaking(args) => shaking::run(args, stdout),
        Command::Balance(args) => balance::run(args, stdout),
        Command::Serve(args) => serve::run(args),
        Command::Engine(args) => engine::run(args, stdout),
        Command::Synth(Synth::Function(args)) => synth_exact::function(args, stdout),
        Command::Synth(Synth::Motion(args)) => synth_exact::motion(args, stdout),
        Command::Synth(Synth::Path(args)) => synth::run_path(args, stdout),
    }
}
