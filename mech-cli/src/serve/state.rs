//! The workbench's state: FILE's path, the last good mechanism with its drawing, the
//! current error (the check's message with the file's line), and a version that counts
//! the changes the page follows.

use crate::{scene, source, svg, Failure};
use mech_core::model::units::Dim;
use mech_core::Mechanism;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

/// The width of the drawing, px.
pub const WIDTH: f64 = 560.0;
/// The smallest height of the drawing, px.
pub const HEIGHT: f64 = 320.0;

/// One input of the mechanism, for its slider.
#[derive(Clone, Debug)]
pub struct Input {
    /// The input joint's name.
    pub name: String,
    /// `rad` or `m`.
    pub unit: &'static str,
    /// The slider's range.
    pub range: (f64, f64),
    /// The input's value in the drawing as written (where a dragged point is placed).
    pub reference: f64,
}

/// A mechanism that passed every check, with what the page draws it in.
#[derive(Debug)]
pub struct Good {
    /// The run-time mechanism.
    pub mechanism: Mechanism,
    /// The map from the drawing (m) to the picture (px), fitted to a turn of the first input.
    pub view: svg::View,
    /// The picture at the reference inputs: the shapes with ids `s0`, `s1`, ...
    pub picture: String,
    /// The inputs, in order.
    pub inputs: Vec<Input>,
    /// The drawing's size, m (the rounding of dragged coordinates follows it).
    pub size: f64,
}

/// What is wrong with FILE: the message (as `mech check` prints it) and its line.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// The whole message (`FILE:LINE:COLUMN: ...` and the excerpt, or an i/o error).
    pub message: String,
    /// The line of FILE it points at, if any.
    pub line: Option<usize>,
}

/// The state the page sees.
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    /// Counts the changes: the mechanism reloaded, an error appeared or went.
    pub version: u64,
    /// The last good mechanism (kept while FILE is wrong or missing).
    pub good: Option<Arc<Good>>,
    /// FILE's error, if it is wrong now.
    pub error: Option<Diagnostic>,
}

/// The workbench of one FILE.
#[derive(Debug)]
pub struct Workbench {
    /// FILE, the only file read or written.
    pub path: PathBuf,
    state: Mutex<(Snapshot, Option<Result<String, String>>)>,
    /// The current version, for the page's event stream.
    pub changes: tokio::sync::watch::Sender<u64>,
    /// Held while FILE is written (one drag at a time).
    pub writing: Mutex<()>,
}

/// Locks `m`, taking the value of a poisoned lock as it is (a panicked holder left it
/// consistent: every update is one assignment).
pub fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Workbench {
    /// The workbench of `path`, read once: an error if FILE cannot be read at all; a file
    /// that is read but wrong is served with its error.
    pub fn open(path: PathBuf) -> Result<Arc<Self>, Failure> {
        source::read(&path)?;
        let wb = Arc::new(Workbench {
            path,
            state: Mutex::new((Snapshot::default(), None)),
            changes: tokio::sync::watch::Sender::new(0),
            writing: Mutex::new(()),
        });
        wb.refresh();
        Ok(wb)
    }

    /// The current state.
    pub fn snapshot(&self) -> Snapshot {
        lock(&self.state).0.clone()
    }

    /// Reads FILE and, when its text (or the error reading it) changed since the last
    /// reading, checks it again: a good mechanism replaces the last one, a bad or missing
    /// file sets the error and keeps the last good mechanism. True when something changed.
    pub fn refresh(&self) -> bool {
        let read = source::read(&self.path).map_err(|f| f.message);
        let key = read.as_ref().map(|(t, _)| t.clone()).map_err(|e| e.clone());
        if lock(&self.state).1.as_ref() == Some(&key) {
            return false;
        }
        let outcome = match &read {
            Ok((text, origin)) => source::parse(text, origin)
                .and_then(good)
                .map_err(|f| diagnostic(&f.message, origin)),
            Err(message) => Err(Diagnostic {
                message: message.clone(),
                line: None,
            }),
        };
        let mut state = lock(&self.state);
        let (snapshot, last) = &mut *state;
        *last = Some(key);
        snapshot.version += 1;
        match outcome {
            Ok(g) => {
                snapshot.good = Some(Arc::new(g));
                snapshot.error = None;
            }
            Err(d) => snapshot.error = Some(d),
        }
        self.changes.send_replace(snapshot.version);
        true
    }
}

/// The diagnostic of `message`, with the line of `origin` it starts with
/// (`origin:LINE:COLUMN: ...`).
pub fn diagnostic(message: &str, origin: &str) -> Diagnostic {
    let line = message
        .strip_prefix(origin)
        .and_then(|r| r.strip_prefix(':'))
        .and_then(|r| r.split(':').next())
        .and_then(|n| n.parse().ok());
    Diagnostic {
        message: message.to_string(),
        line,
    }
}

/// The inputs of `m`: the first over a turn (or ± a quarter of the drawing for a slide),
/// the others around their value in the drawing.
pub fn inputs(m: &Mechanism) -> Vec<Input> {
    let model = m.model();
    let size = scene::size(model);
    (0..m.dof())
        .map(|k| {
            let angle = crate::quantity::input_dims(model, k).0 == Dim::ANGLE;
            let reference = model.reference_input(k);
            let range = if k == 0 {
                crate::draw::default_range(m)
            } else if angle {
                (
                    reference - std::f64::consts::PI,
                    reference + std::f64::consts::PI,
                )
            } else {
                (reference - 0.25 * size, reference + 0.25 * size)
            };
            Input {
                name: model.joints[model.inputs[k]].name.clone(),
                unit: if angle { "rad" } else { "m" },
                range,
                reference,
            }
        })
        .collect()
}

/// A checked mechanism with its drawing: the view fitted to the frames over the first
/// input's range (those that assemble) and the picture at the reference inputs.
fn good(m: Mechanism) -> Result<Good, Failure> {
    let inputs = inputs(&m);
    if inputs.is_empty() {
        return Err(Failure::mechanism(
            "the mechanism has no input: nothing to move",
        ));
    }
    let reference: Vec<f64> = inputs.iter().map(|i| i.reference).collect();
    let first = scene::frame(&m, &reference)?;
    let (a, b) = inputs[0].range;
    let frames: Vec<scene::Frame> = crate::draw::range(&reference, a, b, 90)
        .iter()
        .filter_map(|q| scene::frame(&m, q).ok())
        .collect();
    let view = svg::View::fit(
        frames.iter().chain([&first]).flat_map(|f| f.shapes.iter()),
        WIDTH,
        HEIGHT,
    );
    let mut picture = svg::open_picture(&view);
    picture.push_str(&svg::elements_with_ids(&first, &view));
    picture.push_str("</svg>\n");
    let size = scene::size(m.model());
    Ok(Good {
        mechanism: m,
        view,
        picture,
        inputs,
        size,
    })
}
