//! The HTTP server: the page and its script (built into the binary), the data as JSON,
//! the version as server-sent events, the drag as a POST. Any other path is 404; no
//! request names a file (FILE is the only one read or written). A request must name the
//! host 127.0.0.1 or localhost (a page elsewhere cannot reach the server by a name of its
//! own), and the drag must be JSON from this server's page (a form of another site cannot
//! write FILE).

use super::state::Workbench;
use super::{data, drag};
use crate::Failure;
use axum::extract::{Query, Request, State};
use axum::http::{header, HeaderMap, Method, StatusCode};
use axum::middleware::{self, Next};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::convert::Infallible;
use std::sync::Arc;

/// The page.
pub const PAGE: &str = include_str!("page.html");
/// The page's script.
pub const SCRIPT: &str = include_str!("page.js");

/// The routes: `/`, `/page.js`, `/api/model`, `/api/frame?q=..`, `/api/charts?rest=..&speed=..`,
/// `/api/events` (server-sent events: `version`), `POST /api/drag` (`{"point", "x", "y"}`).
pub fn router(wb: Arc<Workbench>) -> Router {
    Router::new()
        .route("/", get(page))
        .route("/page.js", get(script))
        .route("/api/model", get(model))
        .route("/api/frame", get(frame))
        .route("/api/charts", get(charts))
        .route("/api/events", get(events))
        .route("/api/drag", post(drag))
        .fallback(not_found)
        .layer(middleware::from_fn(guard))
        .with_state(wb)
}

/// The host a request names, if it is this machine's loopback name (`127.0.0.1`,
/// `localhost`, with a port or not).
fn loopback_host(headers: &HeaderMap) -> Option<&str> {
    let host = headers.get(header::HOST)?.to_str().ok()?;
    let name = host.rsplit_once(':').map_or(host, |(n, _)| n);
    matches!(name, "127.0.0.1" | "localhost").then_some(host)
}

/// Refuses a request that names another host (403), and a POST that is not JSON (415) or
/// comes from a page of another origin (403).
async fn guard(req: Request, next: Next) -> Response {
    let headers = req.headers();
    let Some(host) = loopback_host(headers) else {
        return (
            StatusCode::FORBIDDEN,
            "mech serve answers requests for 127.0.0.1 or localhost only\n",
        )
            .into_response();
    };
    if req.method() == Method::POST {
        let json = headers
            .get(header::CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .is_some_and(|v| v.starts_with("application/json"));
        if !json {
            return (
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "a POST to mech serve is application/json\n",
            )
                .into_response();
        }
        let origin = headers.get(header::ORIGIN).and_then(|v| v.to_str().ok());
        if origin.is_some_and(|o| o != format!("http://{host}")) {
            return (
                StatusCode::FORBIDDEN,
                "a POST to mech serve comes from its own page\n",
            )
                .into_response();
        }
    }
    next.run(req).await
}

async fn page() -> Response {
    ([(header::CONTENT_TYPE, "text/html; charset=utf-8")], PAGE).into_response()
}

async fn script() -> Response {
    (
        [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
        SCRIPT,
    )
        .into_response()
}

async fn not_found() -> Response {
    (
        StatusCode::NOT_FOUND,
        "not found: mech serve has /, /page.js and /api/*\n",
    )
        .into_response()
}

/// A failure as a response: 400 for a bad request, 422 for a mechanism that cannot do it.
fn failure(f: Failure) -> Response {
    let code = if f.status == 2 {
        StatusCode::BAD_REQUEST
    } else {
        StatusCode::UNPROCESSABLE_ENTITY
    };
    (code, Json(json!({ "error": f.message }))).into_response()
}

/// Numbers separated by commas (`0.5,1`), named `what` in messages.
fn numbers(text: Option<&String>, what: &str) -> Result<Option<Vec<f64>>, Failure> {
    let Some(t) = text.filter(|t| !t.trim().is_empty()) else {
        return Ok(None);
    };
    t.split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| Failure::usage(format!("{what}: `{v}` is not a finite number")))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

fn no_model() -> Response {
    failure(Failure::mechanism("FILE has no good mechanism yet"))
}

async fn model(State(wb): State<Arc<Workbench>>) -> Response {
    Json(data::model(&wb.snapshot(), &wb.path.display().to_string())).into_response()
}

async fn frame(
    State(wb): State<Arc<Workbench>>,
    Query(p): Query<HashMap<String, String>>,
) -> Response {
    let s = wb.snapshot();
    let Some(g) = &s.good else {
        return no_model();
    };
    let q = match numbers(p.get("q"), "q") {
        Ok(q) => q.unwrap_or_else(|| g.inputs.iter().map(|i| i.reference).collect()),
        Err(f) => return failure(f),
    };
    match data::frame(g, &q) {
        Ok(mut v) => {
            v["version"] = json!(s.version);
            Json(v).into_response()
        }
        Err(f) => failure(f),
    }
}

async fn charts(
    State(wb): State<Arc<Workbench>>,
    Query(p): Query<HashMap<String, String>>,
) -> Response {
    let s = wb.snapshot();
    let Some(g) = &s.good else {
        return no_model();
    };
    let dof = g.inputs.len();
    let rest = match numbers(p.get("rest"), "rest") {
        Ok(r) => r.unwrap_or_else(|| g.inputs.iter().map(|i| i.reference).collect()),
        Err(f) => return failure(f),
    };
    let qd = match numbers(p.get("speed"), "speed") {
        Ok(Some(v)) if v.len() == 1 && dof > 1 => {
            let mut all = vec![0.0; dof];
            all[0] = v[0];
            all
        }
        Ok(v) => v.unwrap_or_else(|| vec![0.0; dof]),
        Err(f) => return failure(f),
    };
    match data::charts(g, &rest, &qd) {
        Ok(mut v) => {
            v["version"] = json!(s.version);
            Json(v).into_response()
        }
        Err(f) => failure(f),
    }
}

async fn events(
    State(wb): State<Arc<Workbench>>,
) -> Sse<impl futures_util::Stream<Item = Result<Event, Infallible>>> {
    let rx = wb.changes.subscribe();
    let stream = futures_util::stream::unfold((rx, true), |(mut rx, first)| async move {
        if !first && rx.changed().await.is_err() {
            return None;
        }
        let v = *rx.borrow_and_update();
        Some((
            Ok(Event::default().event("version").data(v.to_string())),
            (rx, false),
        ))
    });
    Sse::new(stream).keep_alive(KeepAlive::default())
}

async fn drag(State(wb): State<Arc<Workbench>>, body: axum::body::Bytes) -> Response {
    let v: Value = match serde_json::from_slice(&body) {
        Ok(v) => v,
        Err(e) => {
            return failure(Failure::usage(format!(
                "the drag is JSON {{\"point\": NAME, \"x\": X, \"y\": Y}} (m): {e}"
            )))
        }
    };
    let (Some(point), Some(x), Some(y)) = (v["point"].as_str(), v["x"].as_f64(), v["y"].as_f64())
    else {
        return failure(Failure::usage(
            "the drag is JSON {\"point\": NAME, \"x\": X, \"y\": Y} (m)",
        ));
    };
    let point = point.to_string();
    let result = tokio::task::spawn_blocking(move || drag::drag(&wb, &point, x, y)).await;
    match result {
        Ok(Ok(version)) => Json(json!({ "version": version })).into_response(),
        Ok(Err(f)) => failure(f),
        Err(e) => failure(Failure::mechanism(format!("the drag failed: {e}"))),
    }
}
