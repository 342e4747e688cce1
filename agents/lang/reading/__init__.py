"""How a program is read: the parser (sections, clauses, pieces), the semantic
checks, stratification, goals read from text, extension by learned clauses,
printing and transforms of programs."""
