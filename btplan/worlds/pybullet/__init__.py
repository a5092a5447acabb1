"""worlds/pybullet"""
