"""Write your own external agent: block the path as soon as the robot holds the cube.

Any object with a `name` and `act(world, tick) -> list[Disturbance]` is an agent. This
one reacts to the state rather than to a fixed tick, which is the paper's Example 2:
the tree grows, on the fly, a subtree that puts the sphere aside. Run: python examples/custom_agent.py
"""

from pathlib import Path

from btplan.acting.offline import load, run
from btplan.model import Atom
from btplan.worlds.agents import Disturbance

DOMAINS = Path(__file__).resolve().parents[1] / "domains"


class Saboteur:
    name = "saboteur"
    fired = False

    def act(self, world, tick):  # type: ignore[no-untyped-def]
        if self.fired or Atom("holding", ("cube",)) not in world.facts():
            return []
        self.fired = True
        world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
        return [Disturbance(tick, self.name, "rolled the sphere onto tau_goal", "set")]


task = load(str(DOMAINS / "pick_place_obstacle.bt"))
result = run(task, agents=[Saboteur()])
print("reached:", result.reached, "in", result.ticks, "ticks")
for tick, e in result.summary().expansions:
    print(f"tick {tick}: grew at {e.condition} with {', '.join(e.achievers)}")
print("executed:", ", ".join(result.summary().finished))
