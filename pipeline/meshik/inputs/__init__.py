"""Reading inputs: mesh files (pymeshlab, checked first), constraint files, and what `meshik info` and
`meshik validate` say about them."""
