"""layoutdsl: compile a building-layout spec into a verified floor plan for robot simulation."""

__version__ = "0.1.0"
