# Empty dependencies file for springlab-student.
# This may be replaced when dependencies are built.
