"""Where beliefs are inferred: concept rules compiled to code, strata evaluated
bottom-up, incremental maintenance, shared percept rows and the tracker."""
