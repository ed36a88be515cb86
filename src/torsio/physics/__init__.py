"""The physics acting on a structure: bit-rock laws, damping, top drives, the System and
its one description of the dynamics, and the dimensionless formulation."""
