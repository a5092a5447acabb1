"""The two-arm assembly scene: two Franka Pandas across a table build a phone on a fixture.

The paper's second experiment (domains/yumi.bt). Like the package above, nothing heavy
is imported here: pybullet is loaded when a world is built.
"""
