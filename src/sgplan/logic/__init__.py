"""Logic: LTL syntax, checks, LTLf -> DFA, HOA, automaton utilities, equivalence."""
