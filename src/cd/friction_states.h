// An exact solve of a block's 2D Coulomb–Signorini problem by its contacts' states, the fast
// path of the block solve (cd/block_solve.h), which falls back on Lemke's method when it does
// not end. Each contact is guessed open, sticking, or sliding one way or the other; the guess
// fixes a linear system (u_n = 0 where closed, u_t = 0 where sticking, p_t = ±mu p_n where
// sliding, p = 0 where open), whose answer is checked against the law: an open contact that
// would close, a closed one pulling (p_n < 0), a sticking one outside the cone, a sliding one
// moving against its friction change state, and the system is solved again. From
// the state the sweeps left, a few dense solves of the closed contacts' impulses end it, against
// Lemke's path of O(n) pivots over its whole complementarity tableau. It proves nothing when it
// does not end: the state changes may cycle.
#pragma once

#include <vector>

#include "cd/block_problem.h"
#include "cd/contact.h"

namespace cd {

enum class FrictionState { open, stick, slide_positive, slide_negative };  // sliding: p_t = +mu p_n or -mu p_n

// The state of an impulse: open at p_n <= 0, sliding on the cone's edge (to 1e-9), else sticking.
FrictionState state_of(Local2 impulse, double mu);

struct StatesSolve {
  bool solved = false;
  int solves = 0;                     // dense systems solved (rounds, for solve_cycling_by_lemke)
  std::vector<Local2> answer;         // the block's impulses, when solved
  std::vector<FrictionState> states;  // the states of the last system
  std::vector<bool> changed;          // contacts whose state changed on the way (solve_by_states)
};

// The block's problem (cd/block_problem.h) solved from the contacts' `states`. Every contact in a wrong state changes at once
// until three solves in a row bring no fewer such contacts, then one at a time (a different one
// each solve). Stops unsolved after max_solves systems, at a singular one, or at one whose answer
// misses its own equations by more than 1e-8 of the velocities' scale.
StatesSolve solve_by_states(const BlockProblem& problem, std::vector<FrictionState> states, int max_solves);

// Where the states cycle: Lemke's method on the contacts marked `cycling` alone, every other
// contact held in its state (its impulses follow the cycling ones through the held system, a
// complementarity problem of the cycling contacts only). Held contacts that then break their
// state join the cycling ones, for at most max_rounds problems.
StatesSolve solve_cycling_by_lemke(const BlockProblem& problem, const std::vector<FrictionState>& states,
                                   std::vector<bool> cycling, int max_rounds);

}  // namespace cd
