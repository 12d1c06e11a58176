//! `raysandbox shader`: a shader file of the user's own in a window
//! (`app`), or rendered headless (`sandbox`). Its arguments are the
//! sandbox's.

use super::Failure;
use crate::sandbox;

pub use crate::sandbox::ShaderArgs as Args;

pub fn run(args: &Args) -> Result<(), Failure> {
    let result = if args.is_headless() {
        sandbox::run_headless(args)
    } else {
        crate::app::run_sandbox(args)
    };
    result.map_err(Failure::from)
}
