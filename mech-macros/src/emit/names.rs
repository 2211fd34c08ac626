//! The names of the generated types: `<Name>`, `<Name>Params`, `<Name>Loads`,
//! `<Name>Pose`, `<Name>Motion`, `<Name>Forces` (public API) and their field structs
//! (`<Name>ParamsElements` only for a mechanism with force elements, `<Name>ParamsShapes`
//! only for one with links declared by their shapes).

use mech_core::model::Description;
use proc_macro2::Span;
use quote::format_ident;
use syn::Ident;

/// Every generated type name of one mechanism.
pub(crate) struct Names {
    pub main: Ident,
    pub params: Ident,
    pub params_points: Ident,
    pub params_links: Ident,
    pub params_axes: Ident,
    pub params_elements: Ident,
    pub params_shapes: Ident,
    pub loads: Ident,
    pub pose: Ident,
    pub pose_links: Ident,
    pub pose_points: Ident,
    pub motion: Ident,
    pub motion_links: Ident,
    pub motion_points: Ident,
    pub forces: Ident,
    pub forces_joints: Ident,
}

impl Names {
    /// The names of the mechanism declared as `desc`; the struct's own name keeps its span.
    pub fn new(desc: &Description<Span>) -> Self {
        let n = &desc.name.text;
        Names {
            main: Ident::new(n, desc.name.span),
            params: format_ident!("{}Params", n),
            params_points: format_ident!("{}ParamsPoints", n),
            params_links: format_ident!("{}ParamsLinks", n),
            params_axes: format_ident!("{}ParamsAxes", n),
            params_elements: format_ident!("{}ParamsElements", n),
            params_shapes: format_ident!("{}ParamsShapes", n),
            loads: format_ident!("{}Loads", n),
            pose: format_ident!("{}Pose", n),
            pose_links: format_ident!("{}PoseLinks", n),
            pose_points: format_ident!("{}PosePoints", n),
            motion: format_ident!("{}Motion", n),
            motion_links: format_ident!("{}MotionLinks", n),
            motion_points: format_ident!("{}MotionPoints", n),
            forces: format_ident!("{}Forces", n),
            forces_joints: format_ident!("{}ForcesJoints", n),
        }
    }
}
