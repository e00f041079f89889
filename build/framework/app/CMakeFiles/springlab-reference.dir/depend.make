# Empty dependencies file for springlab-reference.
# This may be replaced when dependencies are built.
