//! Repairs of the naga module that work around bugs of naga's own, so that
//! shaders real people write run (docs/sandbox.md, "What runs").
//!
//! **Functions called before their definition.** A prototype
//! (`float f(float x);`) lets a function be called above its definition.
//! naga's GLSL front end adds the function where the prototype is, but
//! wgpu and naga's validator want every function after the ones it calls.
//! The repair puts the functions in that order.
//!
//! **A function that can end without a return.** GLSL leaves the value
//! undefined; naga rejects the function. It returns the zero of its type
//! there, and the user gets a warning at the function's line.
//!
//! **Pointer arguments into a vector, array or struct.** GLSL passes `out`/`inout` arguments by reference, so naga's
//! GLSL front end turns `f(p.x)` (with `void f(inout float x)`) into a call
//! whose argument is a pointer to `p`'s first component. naga's SPIR-V writer
//! only knows pointers to whole variables as call arguments and panics on
//! that one ("Expression [N] is not cached!"). The repair does what GLSL's
//! copy-in/copy-out rule says anyway: the component is copied into a
//! temporary variable before the call, the temporary is passed, and its value
//! is copied back after the call.

use naga::{Block, Expression, Function, Handle, LocalVariable, Span, Statement, Type, TypeInner};

/// Reorders `module.functions` so that every function comes after the
/// functions it calls (GLSL has no recursion, so there is such an order).
pub fn define_before_use(module: &mut naga::Module) {
    let count = module.functions.len();
    let callees: Vec<Vec<usize>> = module
        .functions
        .iter()
        .map(|(_, f)| {
            let mut found = Vec::new();
            calls_in(&f.body, &mut found);
            found
        })
        .collect();
    let mut order = Vec::with_capacity(count);
    let mut state = vec![0u8; count]; // 0 new, 1 being visited, 2 placed
    fn place(f: usize, callees: &[Vec<usize>], state: &mut [u8], order: &mut Vec<usize>) {
        if state[f] != 0 {
            return;
        }
        state[f] = 1;
        for &g in &callees[f] {
            place(g, callees, state, order);
        }
        state[f] = 2;
        order.push(f);
    }
    for f in 0..count {
        place(f, &callees, &mut state, &mut order);
    }
    if order.iter().enumerate().all(|(i, &f)| i == f) {
        return;
    }
    let mut old: Vec<Option<(Function, Span)>> = module
        .functions
        .drain()
        .map(|(_, f, span)| Some((f, span)))
        .collect();
    let mut new_handle = vec![None; count];
    for &f in &order {
        let (function, span) = old[f].take().expect("each function placed once");
        new_handle[f] = Some(module.functions.append(function, span));
    }
    let renumber = |h: Handle<Function>| new_handle[h.index()].expect("every function placed");
    for function in every_function(module) {
        for (_, expression) in function.expressions.iter_mut() {
            if let Expression::CallResult(callee) = expression {
                *callee = renumber(*callee);
            }
        }
        renumber_calls(&mut function.body, &renumber);
    }
}

/// Every function of `module`, its entry points' included.
fn every_function(module: &mut naga::Module) -> impl Iterator<Item = &mut Function> {
    module
        .functions
        .iter_mut()
        .map(|(_, f)| f)
        .chain(module.entry_points.iter_mut().map(|e| &mut e.function))
}

/// The indices of the functions called in `block`.
fn calls_in(block: &Block, found: &mut Vec<usize>) {
    for statement in block.iter() {
        match statement {
            Statement::Call { function, .. } => found.push(function.index()),
            Statement::Block(b) => calls_in(b, found),
            Statement::If { accept, reject, .. } => {
                calls_in(accept, found);
                calls_in(reject, found);
            }
            Statement::Switch { cases, .. } => cases.iter().for_each(|c| calls_in(&c.body, found)),
            Statement::Loop {
                body, continuing, ..
            } => {
                calls_in(body, found);
                calls_in(continuing, found);
            }
            _ => {}
        }
    }
}

fn renumber_calls(block: &mut Block, renumber: &impl Fn(Handle<Function>) -> Handle<Function>) {
    visit_mut(block, &mut |statement| {
        if let Statement::Call { function, .. } = statement {
            *function = renumber(*function);
        }
    });
}

/// Calls `f` on every statement of `block` and of the blocks nested in it.
fn visit_mut(block: &mut Block, f: &mut impl FnMut(&mut Statement)) {
    for statement in block.iter_mut() {
        f(statement);
        match statement {
            Statement::Block(b) => visit_mut(b, f),
            Statement::If { accept, reject, .. } => {
                visit_mut(accept, f);
                visit_mut(reject, f);
            }
            Statement::Switch { cases, .. } => {
                cases.iter_mut().for_each(|c| visit_mut(&mut c.body, f))
            }
            Statement::Loop {
                body, continuing, ..
            } => {
                visit_mut(body, f);
                visit_mut(continuing, f);
            }
            _ => {}
        }
    }
}

/// Gives a function that can end without returning a value (GLSL leaves
/// the value undefined; naga's front end ends the function with a `return`
/// without one, which its validator rejects) the zero of its type there.
/// Returns the span of each function changed, for a warning at its line.
pub fn return_zero_at_end(module: &mut naga::Module) -> Vec<(String, Span)> {
    let mut changed = Vec::new();
    for (handle, function) in module.functions.iter_mut() {
        let Some(result) = &function.result else {
            continue;
        };
        let zero = Expression::ZeroValue(result.ty);
        let expressions = &mut function.expressions;
        let mut found = false;
        visit_mut(&mut function.body, &mut |statement| {
            if let Statement::Return {
                value: value @ None,
            } = statement
            {
                *value = Some(expressions.append(zero.clone(), Span::UNDEFINED));
                found = true;
            }
        });
        if found {
            changed.push((handle, function.name.clone().unwrap_or_default()));
        }
    }
    changed
        .into_iter()
        .map(|(handle, name)| (name, module.functions.get_span(handle)))
        .collect()
}

/// For every function, the pointee type of each parameter passed by pointer.
type PointerParams = Vec<Vec<Option<Handle<Type>>>>;

/// Rewrites every call in `module` that passes a pointer into a composite
/// (not a whole variable) as a copy through a temporary variable.
pub fn spill_pointer_arguments(module: &mut naga::Module) {
    let params: PointerParams = module
        .functions
        .iter()
        .map(|(_, f)| {
            f.arguments
                .iter()
                .map(|a| match module.types[a.ty].inner {
                    TypeInner::Pointer { base, .. } => Some(base),
                    _ => None,
                })
                .collect()
        })
        .collect();
    for function in every_function(module) {
        let body = std::mem::take(&mut function.body);
        function.body = spill_block(body, function, &params);
    }
}

fn spill_block(block: Block, function: &mut Function, params: &PointerParams) -> Block {
    let mut out = Block::with_capacity(block.len());
    for (statement, span) in block.span_into_iter() {
        let statement = match statement {
            Statement::Call {
                function: callee,
                mut arguments,
                result,
            } => {
                let mut copy_back = Vec::new();
                for (i, argument) in arguments.iter_mut().enumerate() {
                    let pointee = params[callee.index()].get(i).copied().flatten();
                    let into_composite = matches!(
                        function.expressions[*argument],
                        Expression::Access { .. } | Expression::AccessIndex { .. }
                    );
                    if let (Some(ty), true) = (pointee, into_composite) {
                        let temporary = copy_in(function, &mut out, *argument, ty, span);
                        copy_back.push((*argument, temporary));
                        *argument = temporary;
                    }
                }
                out.push(
                    Statement::Call {
                        function: callee,
                        arguments,
                        result,
                    },
                    span,
                );
                for (target, temporary) in copy_back {
                    let value = emit(
                        function,
                        &mut out,
                        Expression::Load { pointer: temporary },
                        span,
                    );
                    out.push(
                        Statement::Store {
                            pointer: target,
                            value,
                        },
                        span,
                    );
                }
                continue;
            }
            Statement::Block(b) => Statement::Block(spill_block(b, function, params)),
            Statement::If {
                condition,
                accept,
                reject,
            } => Statement::If {
                condition,
                accept: spill_block(accept, function, params),
                reject: spill_block(reject, function, params),
            },
            Statement::Switch { selector, cases } => Statement::Switch {
                selector,
                cases: cases
                    .into_iter()
                    .map(|mut case| {
                        case.body = spill_block(case.body, function, params);
                        case
                    })
                    .collect(),
            },
            Statement::Loop {
                body,
                continuing,
                break_if,
            } => Statement::Loop {
                body: spill_block(body, function, params),
                continuing: spill_block(continuing, function, params),
                break_if,
            },
            other => other,
        };
        out.push(statement, span);
    }
    out
}

/// A new temporary variable of type `ty` holding what `pointer` points to;
/// returns the pointer to the temporary.
fn copy_in(
    function: &mut Function,
    out: &mut Block,
    pointer: Handle<Expression>,
    ty: Handle<Type>,
    span: Span,
) -> Handle<Expression> {
    let variable = function.local_variables.append(
        LocalVariable {
            name: None,
            ty,
            init: None,
        },
        span,
    );
    let temporary = function
        .expressions
        .append(Expression::LocalVariable(variable), span);
    let value = emit(function, out, Expression::Load { pointer }, span);
    out.push(
        Statement::Store {
            pointer: temporary,
            value,
        },
        span,
    );
    temporary
}

/// Adds an expression that must be evaluated where it stands.
fn emit(
    function: &mut Function,
    out: &mut Block,
    expression: Expression,
    span: Span,
) -> Handle<Expression> {
    let handle = function.expressions.append(expression, span);
    out.push(
        Statement::Emit(naga::Range::new_from_bounds(handle, handle)),
        span,
    );
    handle
}
