; inputs finite with |x| <= 65536 (other batches run the general code)
; 8 points per iteration (ymm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    mov rbp, rsp
     d    sub rsp, 776
    14    and rsp, -32
    18    mov rbx, rdi
    1b    mov r12, rsi
    1e    mov r15, r8
    21    lea r13, [rdx+rdx*2]
    25    add r13, rdx
    28    lea r14, [rcx+rcx*2]
    2c    add r14, rcx
L2:
    2f    cmp r13, r14
    32    jae L3
L4:
    38    mov rax, [rbx]
    3b    vmovups ymm2, [rax+r13*1]
    41    mov rax, [rbx+8]
    45    vmovups ymm3, [rax+r13*1]
    4b    vmovaps ymm4, [rip+L6]
    53    vcmpltps ymm4, ymm4, ymm2
    58    vandps ymm4, ymm4, [rip+L7]
    60    vmulps ymm2, ymm2, [rip+L8]
    68    vxorps ymm3, ymm3, [rip+L9]
    70    vmovaps ymm0, ymm4
    74    vcmpneqps ymm0, ymm0, [rip+L6]
    7d    vmovaps ymm5, ymm3
    81    vblendvps ymm5, ymm5, ymm2, ymm0
    87    mov rax, [r12]
    8b    vmovups [rax+r13*1], ymm5
L5:
    91    add r13, 32
    95    jmp L2
L3:
    9a    mov rax, 0x0
L1:
    9f    mov rsp, rbp
    a2    pop r15
    a4    pop r14
    a6    pop r13
    a8    pop r12
    aa    pop rbp
    ab    pop rbx
    ac    vzeroupper
    af    ret
L6:
    c0    .float 0, 0, 0, 0, 0, 0, 0, 0
L7:
    e0    .float 1, 1, 1, 1, 1, 1, 1, 1
L8:
   100    .float 2, 2, 2, 2, 2, 2, 2, 2
L9:
   120    .float -0, -0, -0, -0, -0, -0, -0, -0
