//! The synchronous driver: everything the app asks for run on an [`Engine`] in this thread,
//! until nothing is left (for `riplab render`, tours played without a terminal, and tests).

use super::app::{App, Command, Msg};
use super::engine::Engine;
use super::protocol::Response;

/// Run everything `app` needs synchronously on `engine`, until nothing is left.
pub fn settle(app: &mut App, engine: &mut Engine) {
    let commands = app.update(Msg::Resize).commands;
    carry_out(app, engine, commands);
}

/// Run `commands` (which `app` asked for) synchronously on `engine`, and whatever the replies
/// ask for in turn, until nothing is left; exports are skipped.
pub fn carry_out(app: &mut App, engine: &mut Engine, mut commands: Vec<Command>) {
    while let Some(command) = commands.pop() {
        let response = match command {
            Command::Solve(req) => {
                let response = engine.solve(&req, &|_| true, &mut |_| {});
                if let Response::Solved {
                    result: Ok(solved), ..
                } = &response
                {
                    let displaced = Engine::displace(solved);
                    commands.extend(app.update(Msg::Worker(response)).commands);
                    displaced
                } else {
                    response
                }
            }
            Command::InfSup(req) => Response::InfSup {
                key: req.key,
                result: Some(engine.inf_sup(req.key)),
            },
            Command::Study(req) => Response::Study {
                generation: req.generation,
                result: Some(engine.study(&req.key, &mut |_| {})),
                key: req.key,
            },
            Command::Stresses(req) => Engine::stresses(&engine.scenario, &req),
            Command::Displace(req) => Engine::displace(&req.solved),
            Command::Export | Command::Suspend | Command::Supersede(_) => continue,
        };
        commands.extend(app.update(Msg::Worker(response)).commands);
    }
}
