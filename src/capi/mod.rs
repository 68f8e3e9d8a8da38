//! The direct C API: the solver without an FMI master.
//!
//! ```text
//! wo_solver_new(lambda, sigma, R_inf, tolerance, &s)     or wo_solver_new_grid(..., degree, elements, edge_scale, &s)
//! wo_solver_advance(s, t_end, edge_stress)                exact in time, any t_end >= t
//! wo_solver_wound_radius / _edge_velocity / _time         scalars
//! wo_solver_node_count, _nodes, _displacement, _velocity  profiles u(r), u_t(r) into caller arrays
//! wo_solver_save_state(s, &st), wo_solver_restore_state(s, st), wo_state_free(st)
//! wo_solver_free(s)
//! wo_series(problem, times, n, R, dRdt)                  a whole R(t) in one call
//! wo_series_sensitivities(problem, times, n, R, dRdt, dRdlambda, dRdR_inf)  and its exact
//!                                                         derivatives in lambda and R_inf
//! wo_profile_series(problem, times, n_t, radii, n_r, u, v) u, u_t at CURRENT radii
//! wo_profile_sensitivities(problem, times, n_t, radii, n_r, rates, edge)  u_t at CURRENT radii and
//!                                                         at the edge, exact derivatives in sigma, lambda, t
//! wo_profile_rates(problem, times, n_t, radii, n_r, rates, edge)  the same and in R_inf and r
//! wo_point_rates(problem, times, radii, n, rates)         wo_profile_rates, a time per point
//! wo_pair_displacement(problem, t_a, t_b, radii, n, d) u(X, t_b) - u(X, t_a) of the point at
//!                                                         CURRENT radius r_i at t_a: a PIV vector's pair
//! wo_last_error()                                         the calling thread's last message
//! ```
//!
//! Every function returns a [`WoStatus`](error::WoStatus) and sets the calling thread's
//! last error message (empty on success). Solvers and states are handles looked up in a
//! table ([`crate::boundary::registry`]), so a NULL, stale or freed handle is an error,
//! never a crash. The safe part is [`solver`]; the `extern "C"` shims are in [`solver_c`];
//! both run behind the panic boundary of [`crate::boundary`], as the FMI functions do.

pub mod error;
mod pairs;
#[cfg(test)]
mod panic_tests;
pub mod profile_rates;
pub mod series;
pub mod series_c;
pub mod solver;
pub mod solver_c;
